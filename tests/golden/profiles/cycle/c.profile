# Based on a, which is in a cycle.
tmcl-profile 1
name c
based-on a
