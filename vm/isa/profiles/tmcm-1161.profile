# TMCM-1161: a one-axis controller/driver (TMC429, TMC262), 10..30 V.
# Its parameters are those the vendor's host libraries list for the module; ranges, access and
# defaults come from the TMCM-1110 manual (the same TMC429 + TMC262 firmware family) and are
# marked unverified unless the TMCL reference (R, sections 4.1, 4.2 and 5.1: every TMCL stepper
# module) confirms them, as is every default no manual gives. Where the reference (older firmware)
# differs, the TMCM-1110 manual's value stays, unverified (docs/errata.md, M15). Every unverified
# fact is listed in docs/profiles.md.
tmcl-profile 1
name tmcm-1161
title "TMCM-1161 (1 axis)"
source F "TMCM-1110 TMCL firmware manual, firmware 1.03, rev. 1.07: the same TMC429 + TMC262 firmware family"
source R "TMCL reference and programming manual, version 2.22 (2008-06-05): every TMCM module"
source P "PyTrinamic pytrinamic/modules/TMCM1161.py"

firmware 1161V100 unverified  # the module number; the version is an example
motors 1 src=P
standalone yes src=F:4.3 unverified
program-memory 2048 eeprom unverified  # as the TMCM-1110: 2048 instructions in EEPROM
user-variables 256 eeprom=56 src=F:6.3 unverified
coordinates 21 src=F:4.5.24 unverified  # 0..20 per motor
parameters listed
motion tmc429 fallback=linear src=P # the TMC429's units (pulse and ramp divisors 153, 154)
motion-constant clock 16000000 src=F:5.5 unverified  # fCLK, Hz
motion-constant velocity-divisor 65536 src=F:5.5 unverified  # µsteps/s = clock * v / (2^pulse_div * 2048 * 32)
motion-constant acceleration-shift 29 src=F:5.5 unverified  # µsteps/s² = clock² * a / 2^(pulse_div + ramp_div + 29)
# The encoder the core simulates (docs/motion.md): 209 counts the shaft through the prescaler, a
# deviation beyond 212 stops the motor and sets 207.
motion-constant encoder 1 src=P  # they list 209, 210 and 212
motion-constant encoder-prescaler 512 src=F:5.4.1 unverified  # prescaler = 210 / 512
motion-constant encoder-prescaler-flags 28 src=F:5.4.1 unverified  # bits 2..4 of 210 select special functions
motion-constant deviation-flag 2 src=P  # 207: '2: deviation error'
motion-constant stall-flag 1 src=P  # 207: '1: stallGuard error', set by a stop on stall (errata E76)
# Commands: those of the TMCM-1110, the same firmware family.
commands 1-15 19-28 30-39 64-71 128-138 src=F:4.4.1 unverified
commands 255 unverified

# Axis parameters. The access E of the TMCM-1110's tables means STAP/RSAP.
axis 0 "Target (next) position" -2147483648..2147483647 RW default=0 unit=μsteps src=F:5,R:4.1,P unverified=range
axis 1 "Actual position" -2147483648..2147483647 RW default=0 unit=μsteps src=F:5,R:4.1,P unverified=range
axis 2 "Target (next) speed" -2047..2047 RW default=0 src=F:5,R:4.1,P  # the table prints '2047' for ±2047 (the TMC429's range)
axis 3 "Actual speed" -2047..2047 R default=0 src=F:5,R:4.1,P  # as 2; the table says RW for a measurement, the TMCL reference R (errata)
axis 4 "Maximum positioning speed" 0..2047 RWE default=1000 src=F:5,R:4.1,P unverified=default
axis 5 "Maximum acceleration" 0..2047 RWE default=1000 src=F:5,R:4.1,P unverified=default
axis 6 "Absolute max. current" 0..255 RWE default=128 src=F:5,R:4.1,P unverified=default
axis 7 "Standby current" 0..255 RWE default=8 src=F:5,R:4.1,P unverified=default
axis 8 "Target position reached" 0..1 R default=1 src=F:5,R:4.1,P
axis 9 "Reference switch status" 0..1 R default=0 src=F:5,R:4.1,P
axis 10 "Right limit switch status" 0..1 R default=0 src=F:5,R:4.1,P
axis 11 "Left limit switch status" 0..1 R default=0 src=F:5,R:4.1,P
axis 12 "Right limit switch disable" 0..1 RWE default=0 src=R:4.1,P unverified=default  # range/access: the TMCL reference
axis 13 "Left limit switch disable" 0..1 RWE default=0 src=R:4.1,P unverified=default
axis 130 "Minimum speed" 0..2047 RWE default=1 src=F:5,R:4.2,P  # 'should always be set 1'
axis 135 "Actual acceleration" 0..2047 R default=0 src=F:5,R:4.2,P
axis 138 "Ramp mode" 0..2 RWE default=0 src=F:5,R:4.2,P unverified=default
axis 140 "Microstep resolution" 0..8 RWE default=8 src=F:5,R:4.2,P unverified=range,default
axis 141 "Reference switch tolerance" 0..4095 RW default=0 unit=μsteps src=R:4.2,P unverified=default not-simulated="the three-switch mode's range in which the reference switch does not stop the motor is not modelled"
axis 149 "Soft stop flag" 0..1 RWE default=0 src=R:4.2,P unverified=default
axis 150 "End switch power down" 0..1 RWE default=0 src=P unverified=range,access,default  # use the standby current when stopped at an end switch
axis 153 "Ramp divisor" 0..13 RWE default=7 src=F:5,R:4.2,P unverified=default  # section 5.5 says 'Default: 0' for both divisors in cells copied from one another; see errata
axis 154 "Pulse divisor" 0..13 RWE default=3 src=F:5,R:4.2,P unverified=default  # as 153
axis 160 "Step interpolation enable" 0..1 RW default=0 src=F:5,P unverified=range,access,default
axis 161 "Double step enable" 0..1 RW default=0 src=F:5,P unverified=range,access,default
axis 162 "Chopper blank time" 0..3 RW default=2 src=F:5,P unverified=range,access,default
axis 163 "Chopper mode" 0..1 RW default=0 src=F:5,P unverified=range,access,default
axis 164 "Chopper hysteresis decrement" 0..3 RW default=0 src=F:5,P unverified=range,access,default
axis 165 "Chopper hysteresis end" -3..12 RW default=0 src=F:5,P unverified=range,access,default
axis 166 "Chopper hysteresis start" 0..8 RW default=0 src=F:5,P unverified=range,access,default
axis 167 "Chopper off time" 0..15 RW default=5 src=F:5,P unverified=range,access,default  # the table: 0 / 2..15 (1 is not a valid setting)
axis 168 "SmartEnergy current minimum (SEIMIN)" 0..1 RW default=0 src=F:5,P unverified=range,access,default
axis 169 "SmartEnergy current down step" 0..3 RW default=0 src=F:5,P unverified=range,access,default
axis 170 "SmartEnergy hysteresis" 0..15 RW default=0 src=F:5,P unverified=range,access,default
axis 171 "SmartEnergy current up step" 0..3 RW default=0 src=F:5,P unverified=range,access,default  # the table says 1..3, its own scaling list 0..3; see errata
axis 172 "SmartEnergy hysteresis start" 0..15 RW default=0 src=F:5,P unverified=range,access,default  # 0 switches coolStep off
axis 173 "stallGuard2 filter enable" 0..1 RW default=0 src=F:5,P unverified=range,access,default
axis 174 "stallGuard2 threshold" -64..63 RW default=0 src=F:5,P unverified=range,access  # 'zero is the starting value'
axis 175 "Slope control high side" 0..3 RW default=3 src=F:5,P unverified=range,access,default
axis 176 "Slope control low side" 0..3 RW default=3 src=F:5,P unverified=range,access,default
axis 177 "Short protection disable" 0..1 RW default=0 src=F:5,P unverified=range,access,default
axis 178 "Short detection timer" 0..3 RW default=0 src=F:5,P unverified=range,access,default
axis 179 "Vsense" 0..1 RW default=0 src=F:5,P unverified=range,access,default
axis 180 "SmartEnergy actual current" 0..31 R default=0 src=F:5,P unverified=range,access  # a status the table calls RW (errata)
axis 181 "Stop on stall" 0..2047 RW default=0 src=F:5,P unverified=range,access,default  # 0: off
axis 182 "SmartEnergy threshold speed" 0..2047 RW default=0 src=F:5,P unverified=range,access,default
axis 183 "SmartEnergy slow run current" 0..255 RW default=0 src=F:5,P unverified=range,access,default
axis 184 "Random TOff mode" 0..1 RW default=0 src=P unverified=range,access,default
axis 193 "Reference search mode" 1..136 RWE default=1 values=1..8,+128 src=F:5,R:4.2,P unverified=range,default  # 1..8, +128 inverts the home switch
axis 194 "Reference search speed" 0..2047 RWE default=0 src=F:5,R:4.2,P unverified=range,default  # 0: the maximum positioning speed 4 (5.3; errata M16)
axis 195 "Reference switch speed" 0..2047 RWE default=0 src=F:5,R:4.2,P unverified=range,default  # 0: a quarter of 4 (5.3; errata M16)
axis 196 "Distance end switches" 0..2147483647 R default=0 unit=μsteps src=F:5,P unverified=range,access
axis 197 "Last reference position" -2147483648..2147483647 R default=0 unit=μsteps src=P unverified=range,access
axis 200 "Boost current" 0..255 RWE default=0 src=P unverified=range,access,default  # 0: the current of parameter 6
axis 204 "Freewheeling" 0..65535 RWE default=0 unit=ms src=F:5,P unverified=range,access,default  # 0: never
axis 206 "Actual load value" 0..1023 R default=0 src=F:5,P unverified=range,access
axis 207 "Extended error flags" 0..3 R default=0 src=P unverified=range,access  # 1: stallGuard error, 2: deviation error
axis 208 "TMC262 driver error flags" 0..255 R default=0 src=F:5,P unverified=range,access
axis 209 "Encoder position" -2147483648..2147483647 RW default=0 unit="encoder steps" src=F:5.4,P unverified=range,access  # the range from section 5.4
axis 210 "Encoder prescaler" 0..65535 RWE default=512 src=F:5.4.1,P unverified=range,access,default  # prescaler = value / 512; bits 2..4 select special functions
axis 212 "Maximum encoder deviation" 0..65535 RWE default=0 unit="encoder steps" src=F:5,P unverified=range,access,default  # 0: off
axis 214 "Power down delay" 1..65535 RWE default=200 unit="10 ms" src=F:5,P unverified=range,access  # 'the standard value is 200'
axis 215 "Absolute resolver value" 0..1023 R default=0 src=P unverified=range,access not-simulated="reads 0: not modelled"
axis 254 "Step/direction mode" 0..1 RWE default=0 src=F:5,P unverified=range,access,default not-simulated="no step/direction input"

# Global parameters, bank 0. Numbers 64..127 are stored in the EEPROM at every SGP (F:6.1): access A.
global 0 65 "RS485 baud rate" 0..11 RWA default=0 src=F:6.1,R:5.1,P unverified=range  # 0 = 9600 baud
global 0 66 "Serial address" 0..255 RWA default=1 src=F:6.1,R:5.1,P unverified=default
global 0 67 "ASCII mode" 0..255 RWA default=0 src=R:5.1,P unverified=range,default not-simulated="there is no ASCII interface"  # bit 0: start in ASCII mode; bits 4, 5: echo
global 0 68 "Serial heartbeat" 0..65535 RWA default=0 unit=ms src=F:6.1,P unverified=range,access,default not-simulated="no heartbeat supervision"  # 0: off; the range is not in the table
global 0 75 "Telegram pause time" 0..255 RWA default=0 src=F:6.1,R:5.1,P unverified=default
global 0 76 "Serial host address" 0..255 RWA default=2 src=F:6.1,R:5.1,P unverified=default
global 0 77 "Auto start mode" 0..1 RWA default=0 src=F:6.1,R:5.1,P
global 0 79 "End switch polarity" 0..3 RWA default=0 src=P unverified=range,access,default not-simulated="the end switches' polarity is not inverted"
global 0 81 "TMCL code protection" 0..3 RWA default=0 src=F:6.1,R:5.1,P unverified=default not-simulated="program memory is not protected"
global 0 84 "Coordinate storage" 0..1 RWA default=0 src=F:6.1,P unverified=range,access  # 0: RAM only (the default, SCO)
global 0 85 "Do not restore user variables" 0..1 RWA default=0 src=F:6.1,P unverified=range,access
global 0 87 "Serial secondary address" 0..255 RWA default=0 src=P unverified=range,access,default not-simulated="the virtual module answers only its address"  # 0: off
global 0 90 "Reverse shaft direction" 0..255 RWA default=0 src=P unverified=range,access,default not-simulated="no motor direction is reversed"  # a bit per motor
global 0 128 "TMCL application status" 0..3 R default=0 src=F:6.1,R:5.1,P
global 0 129 "Download mode" 0..1 R default=0 src=F:6.1,R:5.1,P
global 0 130 "TMCL program counter" 0..2047 R default=0 src=F:6.1,R:5.1,P unverified=range  # the range: the 2048 instructions of program memory
global 0 131 "Last TMCL error" 0..255 R default=0 src=P unverified=range,access not-simulated="reads 0: the last error is not recorded"
global 0 132 "TMCL tick timer" 0..2147483647 RW default=0 unit=ms src=F:6.1,R:5.1,P unverified=range
global 0 133 "Random number" 0..2147483647 R default=0 src=F:6.1,P unverified=range,access
global 0 255 "Suppress reply" 0..1 RW default=0 src=P unverified=range,access,default

# Interrupt configuration, bank 3.
global 3 0 "Timer 0 period" 0..4294967295 RWE default=0 unit=ms src=P unverified=range,access
global 3 1 "Timer 1 period" 0..4294967295 RWE default=0 unit=ms src=P unverified=range,access
global 3 2 "Timer 2 period" 0..4294967295 RWE default=0 unit=ms src=P unverified=range,access
global 3 27 "Left stop switch 0 edge type" 0..3 RWE default=0 src=P unverified=range,access  # 0 off, 1 low-high, 2 high-low, 3 both
global 3 28 "Right stop switch 0 edge type" 0..3 RWE default=0 src=P unverified=range,access
global 3 39 "Input 0 edge type" 0..3 RWE default=0 src=P unverified=range,access
global 3 40 "Input 1 edge type" 0..3 RWE default=0 src=P unverified=range,access
global 3 41 "Input 2 edge type" 0..3 RWE default=0 src=P unverified=range,access
global 3 42 "Input 3 edge type" 0..3 RWE default=0 src=P unverified=range,access

# I/O ports (errata E53, M20): no manual here; the profile's input-change vectors 39 … 42 name four
# inputs (read digital and, as on the TMCM-1110, 12-bit analog); two outputs as the TMCM-1140's.
# Every port is unverified.
port 0 0 "IN0" in digital src=R:3.15 unverified
port 0 1 "IN1" in digital src=R:3.15 unverified
port 0 2 "IN2" in digital src=R:3.15 unverified
port 0 3 "IN3" in digital src=R:3.15 unverified
port 1 0 "IN0" in analog 0..4095 src=R:3.15 unverified
port 1 1 "IN1" in analog 0..4095 src=R:3.15 unverified
port 1 2 "IN2" in analog 0..4095 src=R:3.15 unverified
port 1 3 "IN3" in analog 0..4095 src=R:3.15 unverified
port 2 0 "OUT0" out digital src=R:3.14 unverified
port 2 1 "OUT1" out digital src=R:3.14 unverified

# Interrupt vectors (the TI_ names of Interrupts.inc).
vector 0 TI_TIMER0 "Timer 0" unverified
vector 1 TI_TIMER1 "Timer 1" unverified
vector 2 TI_TIMER2 "Timer 2" unverified
vector 3 TI_TARGET0 "Target position reached, axis 0" unverified
vector 15 TI_STALL0 "stallGuard, axis 0" unverified
vector 21 TI_DEVIATION0 "Deviation, axis 0" unverified
vector 27 TI_STOPL0 "Left stop switch, axis 0" unverified
vector 28 TI_STOPR0 "Right stop switch, axis 0" unverified
vector 39 TI_INPUT0 "Input change 0" unverified
vector 40 TI_INPUT1 "Input change 1" unverified
vector 41 TI_INPUT2 "Input change 2" unverified
vector 42 TI_INPUT3 "Input change 3" unverified
vector 255 TI_GLOBAL "Global interrupt enable" unverified
