# Empty compiler generated dependencies file for ogk.
# This may be replaced when dependencies are built.
