# TMCM-3216: the three-axis module of the TMCM-1290's firmware family (three TMC5240s, EightPoint
# ramps in pps). Its axis parameters are the TMCM-1290's, number for number and name for name
# (PyTrinamic's TMCM3216 and TMCM1290 classes list the same 97), so this profile is based on the
# TMCM-1290's: every inherited row's range, access and default is the TMCM-1290 manual's (no
# TMCM-3216 firmware manual is public to us). What differs comes from PyTrinamic (numbers and
# names; it builds six motors, a slip: its bank-3 stop-switch interrupts are those of axes 0..2)
# and the Zephyr driver (commands, status codes, reference search modes). docs/profiles.md lists
# every unverified fact.
tmcl-profile 1
name tmcm-3216
title "TMCM-3216 (3 axes, TMCM-1290 firmware family)"
based-on tmcm-1290
source M "TMCM-1290 TMCL firmware manual, firmware 1.01: the family's manual, which the inherited rows cite"
source P "PyTrinamic pytrinamic/modules/TMCM3216.py (commit 16bde95)"
source Z "Zephyr drivers/stepper/adi_tmc/tmcm3216/tmcm3216_reg.h (commit a27ef2b)"

firmware 3216V100 unverified  # the module number; the version is an example
motors 3 src=P:GP3  # stop-switch interrupts of axes 0..2 (its motor list of six is a slip)
# Commands: those of the family (the Zephyr driver, src Z, names 1-6 and 9-15 with these numbers
# and the status codes 100, 101, 1-6 of the TMCM-1290 manual's table 4).

# Reference search modes 1..10 as the Zephyr driver names them (TMCL_RFS_MODE_1..10: 7 the home
# switch moving -, 8 moving +, 9 and 10 the encoder's null channel + and -).
axis 193 "Reference search mode" 1..136 RW default=1 values=1..10,65..68,133..136 src=Z,M:4,M:7.1 unverified=default

# Global parameters, bank 0: the TMCM-1290's, and the CAN interface's (PyTrinamic). PyTrinamic
# gives the secondary address as 86, its slip for 87 (TMCM-1290 manual 7.9; docs/errata.md).
global 0 65 "RS485 baud rate" 0..11 RWA default=0 src=P unverified=range,access,default
global 0 69 "CAN bit rate" 2..8 RWA default=8 src=P unverified=range,access,default  # range and default of the TMCM-1260 manual
global 0 70 "CAN reply ID" 0..2047 RWA default=2 src=P unverified=range,access,default
global 0 71 "CAN ID" 0..2047 RWA default=1 src=P unverified=range,access,default
global 0 75 "Telegram pause time" 0..255 RWA default=0 src=P unverified=range,access,default
global 0 78 "I/O mode" 0..7 RWA default=0 unverified not-simulated="the inputs and outputs are separate ports whatever the mode says"  # the TMCM-1290's; PyTrinamic's TMCM3216 lacks it
global 0 82 "CAN heartbeat" 0..65535 RWA default=0 unit=ms src=P unverified=range,access,default  # 0: off
global 0 83 "CAN secondary address" 0..2047 RWA default=0 src=P unverified=range,access,default
global 0 87 "Serial secondary address" 0..255 RWA default=0 src=P unverified=range,access,default not-simulated="the virtual module answers only its address"  # PyTrinamic: 86

# Interrupt configuration, bank 3: the stop switches of axes 1 and 2 and a fourth input.
global 3 29 "Left stop switch 1 trigger transition" 0..3 RW default=0 src=P unverified=range,access
global 3 30 "Right stop switch 1 trigger transition" 0..3 RW default=0 src=P unverified=range,access
global 3 31 "Left stop switch 2 trigger transition" 0..3 RW default=0 src=P unverified=range,access
global 3 32 "Right stop switch 2 trigger transition" 0..3 RW default=0 src=P unverified=range,access
global 3 42 "Input 3 trigger transition" 0..3 RW default=0 src=P unverified=range,access

# I/O ports (PyTrinamic's IO class gives the numbers, not the banks): outputs OUT0..3 in bank 2,
# analog inputs AIN0, AIN1 in bank 1, digital inputs IN0..3 as ports 2..5 of bank 0 (ports 0
# and 1 of bank 0 read AIN0 and AIN1 as digital inputs, as the TMCM-1290's analog line does).
port 0 0 "AIN0" in digital unverified
port 0 1 "AIN1" in digital unverified
port 0 2 "IN0" in digital src=P unverified
port 0 3 "IN1" in digital src=P unverified
port 0 4 "IN2" in digital src=P unverified
port 0 5 "IN3" in digital src=P unverified
port 0 255 "All digital inputs" in bits 0..63 unverified
port 0 0 "Pull-up resistors" out analog 0..63 default=0 unverified
port 1 0 "AIN0" in analog 0..4095 src=P unverified
port 1 1 "AIN1" in analog 0..4095 src=P unverified
port 1 8 "Supply voltage" in analog 0..1000 default=240 unit="0.1 V" unverified
port 1 9 "Temperature" in analog -40..150 default=25 unit="°C" unverified
port 2 0 "OUT0" out digital src=P unverified
port 2 1 "OUT1" out digital src=P unverified
port 2 2 "OUT2" out digital src=P unverified
port 2 3 "OUT3" out digital src=P unverified
port 2 255 "All outputs" out bits 0..15 unverified

# Interrupt vectors: the TMCM-1290's per axis (table 12), for axes 1 and 2 too, and input 3.
vector 4 TI_TARGET1 "Target position reached, axis 1" unverified
vector 5 TI_TARGET2 "Target position reached, axis 2" unverified
vector 10 TI_POSCMP1 "Position compare, axis 1" unverified
vector 11 TI_POSCMP2 "Position compare, axis 2" unverified
vector 16 TI_STALL1 "stallGuard, axis 1" unverified
vector 17 TI_STALL2 "stallGuard, axis 2" unverified
vector 22 TI_DEVIATION1 "Deviation, axis 1" unverified
vector 23 TI_DEVIATION2 "Deviation, axis 2" unverified
vector 29 TI_STOPL1 "Left stop switch, axis 1" src=P:GP3
vector 30 TI_STOPR1 "Right stop switch, axis 1" src=P:GP3
vector 31 TI_STOPL2 "Left stop switch, axis 2" src=P:GP3
vector 32 TI_STOPR2 "Right stop switch, axis 2" src=P:GP3
vector 42 TI_INPUT3 "Input change 3" src=P:GP3
