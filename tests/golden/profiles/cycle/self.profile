# Based on its own name, which means the profile it hides: there is none.
tmcl-profile 1
name self
based-on self
