"""ogk ground tools: nominal trajectories, gain tables, table files."""
