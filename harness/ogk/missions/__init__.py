"""Mission families: truth model family, guidance adapter and paper tables, found by name through
ogk.sil.registry (docs/guides/adding-a-mission.md)."""
