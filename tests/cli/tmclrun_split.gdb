break Trip
run
info registers
continue
delete
continue
quit
