tmcl-profile 1
name other-name
based-on generic
