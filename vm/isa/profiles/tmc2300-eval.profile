# TMC2300-MOTOR-EVAL, TMCL firmware 1.00: one battery-powered TMC2300 StealthChop driver with a
# built-in stepper, reached over UART. Its instruction set is the classic core only: no
# interrupts, no coordinates, none of the commands 37..80 of newer firmware. The manual's
# corrections and the reason for every default it does not give: docs/profiles.md, docs/errata.md.
tmcl-profile 1
name tmc2300-eval
title "TMC2300-MOTOR-EVAL (firmware 1.00)"
source M "TMC2300-MOTOR-EVAL TMCL firmware manual, firmware 1.00, document revision 1.00 (2020-04-23)"

firmware 2300V100 unverified  # version 1.00 from the manual; module number 2300 is ours
include-file TMC2300-MOTOR-EVAL.inc  # ours, in include_files/: the manual's parameter names
motors 1 src=M:1
standalone yes src=M:3.3
program-memory 2048 unverified  # the manual gives no size: 2048 words as in current TMCL firmware
user-variables 256 eeprom=8 src=M:5.2,M:table14  # table 14 marks only 0..7 E
coordinates 0 src=M:table5  # no SCO/GCO/CCO/ACO, so MVP COORD has nothing to move to
parameters listed
motion linear src=M:1
# The stall detection the core simulates (docs/motion.md, errata E74): StallGuard4 in StealthChop
# (187 > 0), 174 the level 206 is compared with, stop on stall 181.
motion-constant stallguard 4 src=M:1  # 'Stall detection StallGuard4 in StealthChop mode'
# Table 5, UF0..UF7 (section 3.6.25), SIO 14 and GIO 15 (the first example program uses SIO,
# the AAP example GIO) and the control commands of table 10 (no 138).
commands 1-12 14-15 19-24 27-28 33-36 64-71 src=M:table5,M:3.6.25
commands 128-137 255 src=M:table10

# Table 11. The access column has no E although STAP/RSAP exist; settings get E, state does not.
axis 0 "Target position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:table11
axis 1 "Actual position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:table11
axis 2 "Target speed" -32768..32767 RW default=0 unit=pps src=M:table11
axis 3 "Actual speed" -32768..32767 R default=0 unit=pps src=M:table11
axis 4 "Maximum positioning speed" 0..32767 RWE default=10000 unit=pps src=M:table11 unverified=default
axis 5 "Maximum acceleration" 0..2147483647 RWE default=10000 unit=pps² src=M:table11 unverified=default
axis 6 "Maximum current" 0..31 RWE default=16 src=M:table11 unverified=default
axis 7 "Standby current" 0..31 RWE default=8 src=M:table11 unverified=default
axis 8 "Position reached flag" 0..1 R default=1 src=M:table11
axis 29 "Measured speed" 0..7999774 R default=0 unit=pps src=M:table11 not-simulated="reads 0 while the motor turns: the driver's measured speed is not computed"
axis 100 "Step generator" -2147483648..2147483647 RW default=0 unit=pps src=M:table11 not-simulated="on the module a non-zero value turns the motor at that many steps per second (the TMC2300's own step generator), in the VM the motor stays"  # the unit from the text
axis 140 "Microstep resolution" 0..8 RWE default=8 src=M:table11 unverified=default
axis 141 "Microstep interpolation enable" 0..1 RWE default=1 src=M:table11 unverified=default
axis 162 "Chopper blank time" 0..3 RWE default=2 src=M:table11 unverified=default
axis 168 "SmartEnergy current minimum (SEIMIN)" 0..1 RWE default=0 src=M:table11 unverified=default
axis 169 "SmartEnergy current down step" 0..3 RWE default=0 src=M:table11 unverified=default
axis 170 "SmartEnergy hysteresis" 0..15 RWE default=0 src=M:table11 unverified=default
axis 171 "SmartEnergy current up step" 0..3 RWE default=0 src=M:table11 unverified=default
axis 172 "SmartEnergy hysteresis start" 0..15 RWE default=0 src=M:table11 unverified=default
axis 174 "StallGuard2 threshold" 0..255 RWE default=0 src=M:table11
axis 180 "SmartEnergy actual current" 0..31 R default=0 src=M:table11
axis 181 "Stop on stall" 0..2147483647 RWE default=0 unit=pps src=M:table11 unverified=default
axis 182 "SmartEnergy threshold speed" 0..1048574 RWE default=0 unit=pps src=M:table11 unverified=default
axis 187 "PWM gradient" 0..15 RWE default=1 src=M:table11 unverified=default
axis 191 "PWM frequency" 0..3 RWE default=1 src=M:table11 unverified=default
axis 192 "PWM autoscale" 0..1 RWE default=1 src=M:table11 unverified=default
axis 204 "Freewheeling mode" 0..3 RWE default=0 src=M:table11 unverified=default
axis 206 "Actual load value" 0..1023 R default=0 src=M:table11
axis 220 "Supply voltage" 0..51 R default=37 unit="0.1 V" src=M:table11 unverified=default  # the table says RW (a measurement) and 1/10V

# Table 13, plus 66 (the SGP/GGP examples) and 85 (section 6.4). Banks: 0 and 2 only.
global 0 65 "UART baud rate" 0..7 RWA default=0 src=M:table13
global 0 66 "Serial address" 1..255 RWA default=1 src=M:3.6.9 unverified=default  # not in table 13: the SGP/GGP examples
global 0 77 "Auto start mode" 0..1 RWA default=0 src=M:table13
global 0 85 "Do not restore user variables" 0..1 RWA default=0 src=M:6.4  # not in table 13; 6.4: restoring at startup is "the default setting"
global 0 128 "TMCL application status" 0..3 R default=0 src=M:table13
global 0 130 "TMCL program counter" 0..2047 R default=0 src=M:table13
global 0 132 "TMCL tick timer" 0..2147483647 RW default=0 unit=ms src=M:table13  # unit from the text
# I/O ports (errata E53): the manual has no GIO/SIO tables; its first program (2.4) enables the
# driver with SIO 0, 2, 1, and its AAP example (3.6.25) reads analog input 0.
port 1 0 "Analog input 0" in analog 0..4095 src=M:3.6.25 unverified  # the AAP example reads it (GIO 0, 1); the range is the 12 bits of the TMCM modules
port 2 0 "TMC2300 enable" out digital src=M:2.4

