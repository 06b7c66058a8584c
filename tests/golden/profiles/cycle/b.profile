# Based on a, which is based on this one.
tmcl-profile 1
name b
based-on a
