"""LEO-to-GEO injection burn ground tools (Pontani & Celani 2021, sec. 6): scenario, trajectory
dynamics with real time as 7th state, the minimum-time nominal (indirect), the VTD-NOG gain tables and
an exact re-solve from displaced states. See docs/design/vtd-nog.md."""
