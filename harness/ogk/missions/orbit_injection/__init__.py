"""LEO-to-GEO injection burn (Pontani & Celani 2021, sec. 6): software-in-the-loop truth models,
dispersions, closed loop, Monte Carlo campaign, report and plots. See docs/guides/sil.md.

Modules: nominal_ref (dense ground nominal), truth (6-DOF and point-mass dynamics), dispersions,
guidance (Guidance protocol + open-loop reference), attitude (AttitudeControl protocol + kernel CPD
batch), sil (closed loop), flights (the campaign's chunk flight and result), report, plots;
ground_tables (ogk tables); family (every verb: ogk tables, run, mc).
"""
