"""The heliocentric Earth-to-Mars rendezvous flown by receding-horizon NMPC (Starek & Kolmanovsky 2012):
truth ("simulation") model and closed loop (docs/design/nmpc.md)."""
