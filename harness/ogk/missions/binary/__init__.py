"""Binary-asteroid proximity transfers (BLT guidance with NRPC; Xiong & Wang is its first user)."""
