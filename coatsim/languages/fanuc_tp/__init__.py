"""Fanuc TP programs in their ASCII form (.LS), as MakeTP and the controller's backups hold them."""
