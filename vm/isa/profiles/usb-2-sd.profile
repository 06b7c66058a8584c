# USB-2-SD, TMCL firmware 1.14: a one-axis step/direction ramp generator with an ABN encoder
# input, USB powered, program memory in RAM only. The manual's corrections and the reason for
# every default it does not give: docs/profiles.md and docs/errata.md.
tmcl-profile 1
name usb-2-sd
title "USB-2-SD (firmware 1.14)"
source M "USB-2-SD TMCL firmware manual, firmware 1.14, document revision 1.01 (2020-01-21)"

firmware 0015V114 src=M:table19 unverified  # version 1.14 from the manual; module number 15 is ours
include-file USB-2-SD.inc  # ours, in include_files/: the manual's parameter names
motors 1 src=M:1
standalone yes src=M:3.3
program-memory 577 ram src=M:1  # "program memory for up to 577 TMCL commands", RAM only
# I/O: the manual has no GIO/SIO tables (the module has step/direction and encoder lines only),
# yet lists SIO and GIO and uses outputs 0 and 3 and analog input 0 in its examples: every port
# number is taken, unchecked (errata E53).
ports any unverified
user-variables 256 eeprom=56 src=M:5.3
coordinates 21 src=M:3.6.19  # 0..20 per motor; 0 is RAM only
parameters listed
motion tmc4361 src=M:1  # linear, SixPoint and S-shaped ramps
# Table 5 and section 3.6 (CALL 80, UF0..UF7); SIO 14 and GIO 15 are used by the interrupt
# example of section 3.5.5.4 (SIO misprinted "SID"); control commands of table 13 and 138.
commands 1-6 9-12 14-15 19-28 30-46 48-51 55-57 64-71 80 src=M:table5,M:3.6
commands 128-138 255 src=M:table13,M:3.6.47

# Table 14, plus 140, 201 and 255 from sections 6.1 and 6.2. No E: the module has no STAP/RSAP.
axis 0 "Target position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:table14
axis 1 "Actual position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:table14
axis 2 "Target speed" -16777215..16777215 RW default=0 unit=pps src=M:table14
axis 3 "Actual speed" -16777215..16777215 R default=0 unit=pps src=M:table14
axis 4 "Maximum positioning speed" 0..16777215 RW default=51200 unit=pps src=M:table14 unverified=default
axis 5 "Maximum acceleration" 0..2147483647 RW default=51200 unit=pps² src=M:table14 unverified=default
axis 8 "Position reached flag" 0..1 R default=1 src=M:table14
axis 14 "Ramp type" 0..1 RW default=0 src=M:table14 unverified=default
axis 15 "Start velocity" 0..16777215 RW default=0 unit=pps src=M:table14 unverified=default
axis 16 "Start acceleration" 0..2147483647 RW default=0 unit=pps² src=M:table14 unverified=default  # 0: same as 5
axis 17 "Maximum deceleration" 0..2147483647 RW default=0 unit=pps² src=M:table14 unverified=default  # 0: same as 5
axis 18 "Break velocity" 0..16777215 RW default=0 unit=pps src=M:table14 unverified=default  # 0: no break point; the table says pps² for a velocity
axis 19 "Final deceleration" 0..2147483647 RW default=0 unit=pps² src=M:table14 unverified=default  # 0: same as 17
axis 20 "Stop velocity" 0..16777215 RW default=0 unit=pps src=M:table14 unverified=default
axis 21 "Stop deceleration" 0..2147483647 RW default=0 unit=pps² src=M:table14 unverified=default  # 0: hard stop at a switch
axis 22 "Bow 1" 0..2147483647 RW default=512000 unit=pps³ src=M:table14 unverified=default
axis 23 "Bow 2" 0..2147483647 RW default=512000 unit=pps³ src=M:table14 unverified=default
axis 24 "Bow 3" 0..2147483647 RW default=512000 unit=pps³ src=M:table14 unverified=default
axis 25 "Bow 4" 0..2147483647 RW default=512000 unit=pps³ src=M:table14 unverified=default
axis 26 "Virtual stop left" -2147483648..2147483647 RW default=0 unit=μsteps src=M:table14 unverified=default
axis 27 "Virtual stop right" -2147483648..2147483647 RW default=0 unit=μsteps src=M:table14 unverified=default
axis 28 "Virtual stop enable" 0..3 RW default=0 src=M:table14 unverified=default
axis 29 "Virtual stop mode" 0..2 RW default=0 src=M:table14 unverified=default  # the table says R: a typo
axis 35 "Bow scaling factor" 1..255 RW default=1 src=M:table14
axis 127 "Relative positioning option" 0..2 RW default=0 src=M:table14 unverified=default  # the table says 0/1 but lists 0..2
axis 131 "Measured speed" -2147483648..2147483647 R default=0 unit=pps src=M:table14
axis 132 "Current measured speed" -2147483648..2147483647 R default=0 unit=pps src=M:table14
axis 140 "Microstep resolution" 0..8 RW default=8 src=M:6.2  # not in table 14
axis 201 "Encoder special functions" 0..65535 RW default=0 src=M:6.1 unverified=default not-simulated="the encoder's special functions (null channel, latches) are not modelled"  # not in table 14
axis 202 "Motor full step resolution" 0..65535 RW default=200 unit=fullsteps/round src=M:table14
axis 207 "Extended error flags" 0..2 R default=0 src=M:table14
axis 209 "Encoder position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:table14
axis 210 "Encoder resolution" -65535..65535 RW default=51200 src=M:table14 unverified=default
axis 212 "Maximum encoder deviation" 0..2147483647 RW default=0 unit="encoder steps" src=M:table14 unverified=default
axis 213 "Maximum velocity deviation" 0..2147483647 RW default=0 unit=pps src=M:table14 unverified=default not-simulated="the velocity deviation check is not modelled"  # the table says encoder steps
axis 251 "Reverse shaft" 0..1 RW default=0 src=M:table14 unverified=default
axis 255 "Unit mode" 0..1 RW default=1 src=M:6.2  # not in table 14

# Table 16, plus 66, 76, 77, 84 and 85, which the text uses. Numbers 64..127 are stored in the
# EEPROM on every SGP (section 5.1): access A.
global 0 66 "Serial address" 1..255 RWA default=1 src=M:3.6.7 unverified=default  # the SGP/GGP examples
global 0 76 "Serial host address" 1..255 RWA default=2 unverified=exists,default  # no word of it in the manual
global 0 77 "Auto start mode" 0..1 RWA default=0 src=M:7.7 unverified=default
global 0 84 "Store coordinates in EEPROM" 0..1 RWA default=0 src=M:3.6.19
global 0 85 "Do not restore user variables" 0..1 RWA default=0 src=M:7.4
global 0 86 "Step pulse length" 0..255 RWA default=32 unit="1/16 µs" src=M:table16 unverified=default  # unit from the text: 32 = 2 µs
global 0 128 "TMCL application status" 0..3 R default=0 src=M:table16
global 0 129 "Download mode" 0..1 R default=0 src=M:table16
global 0 130 "TMCL program counter" 0..576 R default=0 src=M:table16
global 0 132 "TMCL tick timer" 0..2147483647 RW default=0 unit=ms src=M:table16  # unit from the text
global 0 133 "Random number" 0..2147483647 RW default=0 src=M:table16
global 0 255 "Suppress reply" 0..1 RW default=0 src=M:table16  # "will be reset to 0 on startup"

# Table 18: interrupt configuration. Timer periods are unsigned 32-bit values.
global 3 0 "Timer 0 period (ms)" 0..4294967295 RW default=0 unit=ms src=M:table18 unverified=default
global 3 1 "Timer 1 period (ms)" 0..4294967295 RW default=0 unit=ms src=M:table18 unverified=default
global 3 2 "Timer 2 period (ms)" 0..4294967295 RW default=0 unit=ms src=M:table18 unverified=default
global 3 27 "Stop left 0 trigger transition" 0..3 RW default=0 src=M:table18 unverified=default
global 3 28 "Stop right 0 trigger transition" 0..3 RW default=0 src=M:table18 unverified=default

# Table 11. TI_TIMER0 and TI_GLOBAL are the names the manual shows; the others are ours.
vector 0 TI_TIMER0 "Timer 0" src=M:table11
vector 1 TI_TIMER1 "Timer 1" src=M:table11
vector 2 TI_TIMER2 "Timer 2" src=M:table11
vector 3 TI_TARGET0 "Target position reached, axis 0" src=M:table11
vector 15 TI_STALL0 "stallGuard, axis 0" src=M:table11
vector 21 TI_DEVIATION0 "Deviation, axis 0" src=M:table11
vector 27 TI_STOPL0 "Left stop switch, axis 0" src=M:table11
vector 28 TI_STOPR0 "Right stop switch, axis 0" src=M:table11
vector 255 TI_GLOBAL "Global interrupt enable" src=M:table11
