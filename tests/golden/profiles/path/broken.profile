tmcl-profile 1
name broken
motors many
