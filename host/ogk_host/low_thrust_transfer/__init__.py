"""Apophis CubeSat ground tool (Wang & Topputo 2020): scenario, dynamics, fuel-optimal indirect
solver and the Fourier initial weights of the MPSP guidance. See docs/design/apophis-nominal.md."""
