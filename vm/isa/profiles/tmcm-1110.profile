# TMCM-1110 (stepRocker), TMCL firmware 1.03: a one-axis controller/driver board (TMC429 motion
# controller, TMC262 driver), whose TMC429 has three axes: axis 0 drives the motor, axes 1 and 2
# the step/direction outputs for two more boards. Ranges and access from the manual's tables;
# parameters of newer firmware (the vendor's host library) are added with the source named.
# Every unverified fact is listed in docs/profiles.md.
tmcl-profile 1
name tmcm-1110
alias steprocker
title "TMCM-1110 stepRocker (firmware 1.03)"
source M "TMCM-1110 TMCL firmware manual, firmware 1.03, document revision 1.07 (2012-04-11)"
source R "TMCL reference and programming manual, version 2.22 (2008-06-05): every TMCM module"
source P "PyTrinamic pytrinamic/modules/TMCM1110.py: the parameters of newer firmware"

firmware 1110V103 src=M:4.5.38  # version 1.03; the manual's example string is 6110V100
motors 3 src=M:1,M:4.4.2.6.3  # 'end switches for all three axes'; axis 0 has the driver
standalone yes src=M:4.3
program-memory 2048 eeprom src=M:1,M:4.2.1  # 'memory for up to 2048 TMCL commands', 'program EEPROM'
user-variables 256 eeprom=56 src=M:6.3
coordinates 21 src=M:4.5.24  # 'up to 20 position values' per axis, and 0
parameters listed
motion tmc429 fallback=linear src=M:1,M:5.5 # the TMC429's units (pulse and ramp divisors 153, 154)
motion-constant clock 16000000 src=M:5.5  # fCLK, Hz
motion-constant velocity-divisor 65536 src=M:5.5  # µsteps/s = clock * v / (2^pulse_div * 2048 * 32)
motion-constant acceleration-shift 29 src=M:5.5  # µsteps/s² = clock² * a / 2^(pulse_div + ramp_div + 29)
# The encoder the core simulates (docs/motion.md): 209 counts the shaft through the prescaler, a
# deviation beyond 212 stops the motor and sets 207.
motion-constant encoder 1 src=M:5.4
motion-constant encoder-prescaler 512 src=M:5.4.1  # prescaler = 210 / 512
motion-constant encoder-prescaler-flags 28 src=M:5.4.1  # bits 2..4 of 210 select special functions
motion-constant deviation-flag 2 src=P  # 207: '2: deviation error'
motion-constant stall-flag 1 src=P  # 207: '1: stallGuard error', set by a stop on stall (errata E76)
# Commands: table 4.4.1, CLE 36 (4.5.31), UF0..UF7 (4.5.36), 138 (4.5.37) and the control commands
# (4.5.38; 128..135 as in every TMCL module, the TMCL reference 3.35). 255 (software reset) is not
# in the manual but in newer firmware.
commands 1-15 19-28 30-39 64-71 src=M:4.4.1,M:4.5.31,M:4.5.36
commands 128-138 src=M:4.5.37,M:4.5.38,R:3.35
commands 255 unverified

# Axis parameters. Section 5; the manual's access E means STAP/RSAP.
# Axes 1 and 2 have no driver: 6, 7, 140, 160..184 and 204..254 are axis 0's only (section 5).
axis 0 "Target (next) position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:5
axis 1 "Actual position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:5
axis 2 "Target (next) speed" -2047..2047 RW default=0 src=M:5  # the table prints '2047' for ±2047 (the TMC429's range)
axis 3 "Actual speed" -2047..2047 R default=0 src=M:5  # as 2; the table says RW for a measurement, the TMCL reference R (errata)
axis 4 "Maximum positioning speed" 0..2047 RWE default=1000 src=M:5 unverified=default
axis 5 "Maximum acceleration" 0..2047 RWE default=1000 src=M:5 unverified=default
axis 6 "Absolute max. current" 0..255 RWE default=128 src=M:5 unverified=default
axis 7 "Standby current" 0..255 RWE default=8 src=M:5 unverified=default
axis 8 "Target position reached" 0..1 R default=1 src=M:5
axis 9 "Reference switch status" 0..1 R default=0 src=M:5
axis 10 "Right limit switch status" 0..1 R default=0 src=M:5
axis 11 "Left limit switch status" 0..1 R default=0 src=M:5
axis 12 "Right limit switch disable" 0..1 RWE default=0 src=R:4.1,P unverified=default  # range/access: the TMCL reference
axis 13 "Left limit switch disable" 0..1 RWE default=0 src=R:4.1,P unverified=default
axis 130 "Minimum speed" 0..2047 RWE default=1 src=M:5  # 'should always be set 1'
axis 135 "Actual acceleration" 0..2047 R default=0 src=M:5
axis 138 "Ramp mode" 0..2 RWE default=0 src=M:5 unverified=default
axis 140 "Microstep resolution" 0..8 RWE default=8 src=M:5 unverified=default
axis 141 "Reference switch tolerance" 0..4095 RW default=0 unit=μsteps src=R:4.2,P unverified=default not-simulated="the three-switch mode's range in which the reference switch does not stop the motor is not modelled"
axis 149 "Soft stop flag" 0..1 RWE default=0 src=R:4.2,P unverified=default
axis 150 "End switch power down" 0..1 RWE default=0 src=P unverified=range,access,default  # use the standby current when stopped at an end switch
axis 153 "Ramp divisor" 0..13 RWE default=7 src=M:5 unverified=default  # section 5.5 says 'Default: 0' for both divisors in cells copied from one another; see errata
axis 154 "Pulse divisor" 0..13 RWE default=3 src=M:5 unverified=default  # as 153
axis 160 "Step interpolation enable" 0..1 RW default=0 src=M:5 unverified=default
axis 161 "Double step enable" 0..1 RW default=0 src=M:5 unverified=default
axis 162 "Chopper blank time" 0..3 RW default=2 src=M:5 unverified=default
axis 163 "Chopper mode" 0..1 RW default=0 src=M:5 unverified=default
axis 164 "Chopper hysteresis decrement" 0..3 RW default=0 src=M:5 unverified=default
axis 165 "Chopper hysteresis end" -3..12 RW default=0 src=M:5 unverified=default
axis 166 "Chopper hysteresis start" 0..8 RW default=0 src=M:5 unverified=default
axis 167 "Chopper off time" 0..15 RW default=5 src=M:5 unverified=default  # the table: 0 / 2..15 (1 is not a valid setting)
axis 168 "SmartEnergy current minimum (SEIMIN)" 0..1 RW default=0 src=M:5 unverified=default
axis 169 "SmartEnergy current down step" 0..3 RW default=0 src=M:5 unverified=default
axis 170 "SmartEnergy hysteresis" 0..15 RW default=0 src=M:5 unverified=default
axis 171 "SmartEnergy current up step" 0..3 RW default=0 src=M:5 unverified=default  # the table says 1..3, its own scaling list 0..3; see errata
axis 172 "SmartEnergy hysteresis start" 0..15 RW default=0 src=M:5 unverified=default  # 0 switches coolStep off
axis 173 "stallGuard2 filter enable" 0..1 RW default=0 src=M:5 unverified=default
axis 174 "stallGuard2 threshold" -64..63 RW default=0 src=M:5  # 'zero is the starting value'
axis 175 "Slope control high side" 0..3 RW default=3 src=M:5 unverified=default
axis 176 "Slope control low side" 0..3 RW default=3 src=M:5 unverified=default
axis 177 "Short protection disable" 0..1 RW default=0 src=M:5 unverified=default
axis 178 "Short detection timer" 0..3 RW default=0 src=M:5 unverified=default
axis 179 "Vsense" 0..1 RW default=0 src=M:5 unverified=default
axis 180 "SmartEnergy actual current" 0..31 R default=0 src=M:5  # a status the table calls RW (errata)
axis 181 "Stop on stall" 0..2047 RW default=0 src=M:5 unverified=default  # 0: off
axis 182 "SmartEnergy threshold speed" 0..2047 RW default=0 src=M:5 unverified=default
axis 183 "SmartEnergy slow run current" 0..255 RW default=0 src=M:5 unverified=default
axis 184 "Random TOff mode" 0..1 RW default=0 src=P unverified=range,access,default
axis 193 "Reference search mode" 1..136 RWE default=1 values=1..8,+128 src=M:5 unverified=default  # 1..8, +128 inverts the home switch
axis 194 "Reference search speed" 0..2047 RWE default=0 src=M:5 unverified=default  # 0: the maximum positioning speed 4 (5.3; errata M16)
axis 195 "Reference switch speed" 0..2047 RWE default=0 src=M:5 unverified=default  # 0: a quarter of 4 (5.3; errata M16)
axis 196 "Distance end switches" 0..2147483647 R default=0 unit=μsteps src=M:5
axis 204 "Freewheeling" 0..65535 RWE default=0 unit=ms src=M:5 unverified=default  # 0: never
axis 206 "Actual load value" 0..1023 R default=0 src=M:5
axis 207 "Extended error flags" 0..3 R default=0 src=P unverified=range,access  # 1: stallGuard error, 2: deviation error
axis 208 "TMC262 driver error flags" 0..255 R default=0 src=M:5
axis 209 "Encoder position" -2147483648..2147483647 RW default=0 unit="encoder steps" src=M:5.4  # the range from section 5.4
axis 210 "Encoder prescaler" 0..65535 RWE default=512 src=M:5.4.1 unverified=default  # prescaler = value / 512; bits 2..4 select special functions
axis 212 "Maximum encoder deviation" 0..65535 RWE default=0 unit="encoder steps" src=M:5 unverified=default  # 0: off
axis 213 "Group index" 0..255 RW default=0 src=R:4.2,P unverified=range,access,default not-simulated="group moves are not modelled"  # not in the manual; the reference gives 0..255 RW for the TMCM-610, -611, -612 and -34x only (errata M15)
axis 214 "Power down delay" 1..65535 RWE default=200 unit="10 ms" src=M:5  # 'the standard value is 200'
axis 254 "Step/direction mode" 0..1 RWE default=0 src=M:5 unverified=default not-simulated="no step/direction input"

# Global parameters, bank 0. Numbers 64..127 are stored in the EEPROM at every SGP (M:6.1): access A.
global 0 64 "EEPROM magic" 0..255 RWA default=228 src=M:6.1 not-simulated="a value other than 228 does not restore the factory defaults at the next power-on"  # not $E4 (228): factory defaults at the next power-up
global 0 65 "RS485 baud rate" 0..11 RWA default=0 src=M:6.1  # 0 = 9600 baud
global 0 66 "Serial address" 0..255 RWA default=1 src=M:6.1 unverified=default
global 0 68 "Serial heartbeat" 0..65535 RWA default=0 unit=ms src=M:6.1 unverified=default not-simulated="no heartbeat supervision"  # 0: off; the range is not in the table
global 0 69 "CAN bit rate" 2..8 RWA default=8 src=M:6.1  # 8 = 1000 kbit/s
global 0 70 "CAN reply ID" 0..2047 RWA default=2 src=M:6.1
global 0 71 "CAN ID" 0..2047 RWA default=1 src=M:6.1
global 0 73 "Configuration EEPROM lock flag" 0..4321 RWA default=0 src=M:6.1 unverified=default not-simulated="the lock is tmclrun --serve's option, not this flag"  # reads 0/1; write 1234 to lock, 4321 to unlock
global 0 75 "Telegram pause time" 0..255 RWA default=0 src=M:6.1 unverified=default
global 0 76 "Serial host address" 0..255 RWA default=2 src=M:6.1 unverified=default
global 0 77 "Auto start mode" 0..1 RWA default=0 src=M:6.1
global 0 78 "IO mode" 0..255 RWA default=0 src=P unverified=range,access,default
global 0 79 "End switch polarity" 0..3 RWA default=0 src=P unverified=range,access,default not-simulated="the end switches' polarity is not inverted"
global 0 81 "TMCL code protection" 0..3 RWA default=0 src=M:6.1 unverified=default not-simulated="program memory is not protected"
global 0 82 "CAN heartbeat" 0..65535 RWA default=0 unit=ms src=M:6.1 unverified=default  # 0: off; the range is not in the table
global 0 83 "CAN secondary address" 0..2047 RWA default=0 src=M:6.1 unverified=default  # 0: off
global 0 84 "Coordinate storage" 0..1 RWA default=0 src=M:6.1  # 0: RAM only (the default, SCO)
global 0 85 "Do not restore user variables" 0..1 RWA default=0 src=M:6.1
global 0 86 "Step pulse length" 0..15 RWA default=0 src=M:6.1  # 0 = 1 µs
global 0 87 "Serial secondary address" 0..255 RWA default=0 src=P unverified=range,access,default not-simulated="the virtual module answers only its address"  # 0: off
global 0 90 "Reverse shaft direction" 0..255 RWA default=0 src=P unverified=range,access,default not-simulated="no motor direction is reversed"  # a bit per motor
global 0 128 "TMCL application status" 0..3 R default=0 src=M:6.1
global 0 129 "Download mode" 0..1 R default=0 src=M:6.1
global 0 130 "TMCL program counter" 0..2047 R default=0 src=M:6.1  # the range: the 2048 instructions of program memory
global 0 132 "TMCL tick timer" 0..2147483647 RW default=0 unit=ms src=M:6.1
global 0 133 "Random number" 0..2147483647 R default=0 src=M:6.1
global 0 255 "Suppress reply" 0..1 RW default=0 src=P unverified=range,access,default

# Interrupt configuration, bank 3.
global 3 0 "Timer 0 period" 0..4294967295 RWE default=0 unit=ms src=M:6.4
global 3 1 "Timer 1 period" 0..4294967295 RWE default=0 unit=ms src=M:6.4
global 3 2 "Timer 2 period" 0..4294967295 RWE default=0 unit=ms src=M:6.4
global 3 27 "Left stop switch 0 edge type" 0..3 RWE default=0 src=M:6.4  # 0 off, 1 low-high, 2 high-low, 3 both
global 3 28 "Right stop switch 0 edge type" 0..3 RWE default=0 src=M:6.4
global 3 29 "Left stop switch 1 edge type" 0..3 RWE default=0 src=M:6.4
global 3 30 "Right stop switch 1 edge type" 0..3 RWE default=0 src=M:6.4
global 3 31 "Left stop switch 2 edge type" 0..3 RWE default=0 src=M:6.4
global 3 32 "Right stop switch 2 edge type" 0..3 RWE default=0 src=M:6.4
global 3 39 "Input 0 edge type" 0..3 RWE default=0 src=M:6.4
global 3 40 "Input 1 edge type" 0..3 RWE default=0 src=M:6.4
global 3 41 "Input 2 edge type" 0..3 RWE default=0 src=M:6.4
global 3 42 "Input 3 edge type" 0..3 RWE default=0 src=M:6.4
global 3 43 "Input 4 edge type" 0..3 RWE default=0 src=P unverified=range,access not-simulated="the profile has no digital input 4 (GIO 4, 0 lists inputs 0 to 3, manual 4.5.15.1), so no input change raises vector 43"
global 3 44 "Input 5 edge type" 0..3 RWE default=0 src=P unverified=range,access not-simulated="the profile has no digital input 5 (GIO 5, 0 lists inputs 0 to 3, manual 4.5.15.1), so no input change raises vector 44"
global 3 45 "Input 6 edge type" 0..3 RWE default=0 src=P unverified=range,access not-simulated="the profile has no digital input 6 (GIO 6, 0 lists inputs 0 to 3, manual 4.5.15.1), so no input change raises vector 45"

# I/O ports (errata E53): the GIO/SIO tables of sections 4.5.14 and 4.5.15. AIN_0 reads as a
# digital (bank 0) and an analog (bank 1) input at once; bank 2 reads the outputs back.
port 0 0 "AIN_0" in digital src=M:4.5.15.1
port 0 1 "PWMD0" in digital src=M:4.5.15.1
port 0 2 "PWMD1" in digital src=M:4.5.15.1
port 0 3 "PWMD2" in digital src=M:4.5.15.1
port 1 0 "AIN_0" in analog 0..4095 src=M:4.5.15.2
port 1 1 "ADC7 (+VS)" in analog 0..4095 src=M:4.5.15.2
port 1 2 "ADC6 (+5V)" in analog 0..4095 src=M:4.5.15.2
port 2 0 "OpenDrain_1" out digital src=M:4.5.14,M:4.5.15.3
port 2 1 "OpenDrain_2" out digital src=M:4.5.14,M:4.5.15.3
port 2 2 "PWMU0" out digital src=M:4.5.14,M:4.5.15.3
port 2 3 "PWMU1" out digital src=M:4.5.14,M:4.5.15.3
port 2 4 "PWMU2" out digital src=M:4.5.14,M:4.5.15.3

# Interrupt vectors (the TI_ names of Interrupts.inc).
vector 0 TI_TIMER0 "Timer 0" src=M:4.4.2.6.3
vector 1 TI_TIMER1 "Timer 1" src=M:4.4.2.6.3
vector 2 TI_TIMER2 "Timer 2" src=M:4.4.2.6.3
vector 3 TI_TARGET0 "Target position reached, axis 0" src=M:4.4.2.6.3
vector 4 TI_TARGET1 "Target position reached, axis 1" src=M:4.4.2.6.3
vector 5 TI_TARGET2 "Target position reached, axis 2" src=M:4.4.2.6.3
vector 15 TI_STALL0 "stallGuard, axis 0" src=M:4.4.2.6.3
vector 21 TI_DEVIATION0 "Deviation, axis 0" src=M:4.4.2.6.3
vector 27 TI_STOPL0 "Left stop switch, axis 0" src=M:4.4.2.6.3
vector 28 TI_STOPR0 "Right stop switch, axis 0" src=M:4.4.2.6.3
vector 29 TI_STOPL1 "Left stop switch, axis 1" src=M:4.4.2.6.3
vector 30 TI_STOPR1 "Right stop switch, axis 1" src=M:4.4.2.6.3
vector 31 TI_STOPL2 "Left stop switch, axis 2" src=M:4.4.2.6.3
vector 32 TI_STOPR2 "Right stop switch, axis 2" src=M:4.4.2.6.3
vector 39 TI_INPUT0 "Input change 0" src=M:4.4.2.6.3
vector 40 TI_INPUT1 "Input change 1" src=M:4.4.2.6.3
vector 41 TI_INPUT2 "Input change 2" src=M:4.4.2.6.3
vector 42 TI_INPUT3 "Input change 3" src=M:4.4.2.6.3
vector 255 TI_GLOBAL "Global interrupt enable" src=M:4.4.2.6.3
vector 43 TI_INPUT4 "Input change 4" unverified
vector 44 TI_INPUT5 "Input change 5" unverified
vector 45 TI_INPUT6 "Input change 6" unverified
