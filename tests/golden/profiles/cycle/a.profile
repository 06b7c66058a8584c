# Based on b, which is based on this one: a cycle (based-on-cycle.run).
tmcl-profile 1
name a
based-on b
