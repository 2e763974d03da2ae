"""The paper's Apophis mission flown by the kernel's MPSP (Wang & Topputo 2020, Tables 3-6).

cases.py builds the guidance configuration from the ground nominal and the perturbation cases;
reference.py caches the ground fuel-optimal re-solves of the same cases; report.py compares with the
paper's tables; plots.py draws Figs. 3-4-like figures. Command line: `ogk mpsp apophis`
(harness/ogk/cli/cmd_mpsp.py, docs/guides/mpsp-cli.md).
"""
