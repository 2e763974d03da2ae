# Empty dependencies file for ogk_objects.
# This may be replaced when dependencies are built.
