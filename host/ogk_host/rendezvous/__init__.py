"""Low-thrust heliocentric rendezvous (Starek & Kolmanovsky 2012): scenarios, models and the open-loop
optimal control problems of the ground (docs/design/nmpc.md)."""
