# TMCM-1290, TMCL firmware 1.01: a one-axis controller/driver with a TMC5240 (EightPoint ramps
# in pps, StallGuard2, CoolStep), an ABN encoder input, three GPIOs and two stop switches. Facts
# from its firmware manual (converted text; rows the conversion garbled are checked against the
# prose, docs/errata.md); PyTrinamic adds the StallGuard4 rows 220-223. Its motion core is
# `tmc5240`: the EightPoint ramp in pps with these parameter numbers (docs/motion.md). The
# TMCM-3216 is based on this profile. Every unverified fact is listed in docs/profiles.md.
tmcl-profile 1
name tmcm-1290
title "TMCM-1290 (firmware 1.01)"
source M "TMCM-1290 TMCL firmware manual, firmware 1.01, document revision 0 (2024-01)"
source P "PyTrinamic pytrinamic/modules/TMCM1290.py (commit 16bde95)"

firmware 1290V101 unverified  # version 1.01 from the manual (table 25); it shows no version string
motors 1 src=M:1
standalone yes src=M:3.3
program-memory 2048 eeprom unverified  # the manual gives no size ('download a program into the EEPROM', 3.3)
user-variables 256 eeprom=56 src=M:5.3
coordinates 21 src=M:3.6.22  # 'up to 20 position values' per axis, and 0
parameters listed
motion tmc5240 fallback=tmc5160 src=M:1.3,M:7.5,M:7.6  # pps and pps², EightPoint ramps
# The encoder the core simulates (docs/motion.md): 209 counts the shaft in microsteps (7.2: "the
# module automatically converts the encoder resolution to the motor microstep resolution"), a
# deviation beyond 212 stops the motor and sets 207, which reading clears.
motion-constant encoder 1 src=M:7.2
motion-constant encoder-prescaler 0 src=M:7.2
motion-constant deviation-flag 2 src=M:4  # 207: '2 deviation error'
motion-constant error-flags-read-clears 1 src=M:4  # 207: 'cleared automatically when this parameter is read out'
motion-constant stall-flag 1 src=M:4  # 207: '1 StallGuard error'
# Commands: table 5 (no STAP/RSAP, no SAC), the new commands of table 13, UF0..UF7 (3.6.49),
# 138 (3.6.50) and the control commands of table 14.
commands 1-6 9-15 19-28 30-46 48-51 55-57 64-71 80 src=M:table5,M:table13,M:3.6.49
commands 128-138 255 src=M:table14,M:3.6.50

# Axis parameters (table 16).
axis 0 "Target position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:4
axis 1 "Actual position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:4
axis 2 "Target speed" -7999774..7999774 RW default=0 unit=pps src=M:4
axis 3 "Actual speed" -7999774..7999774 R default=0 unit=pps src=M:4
axis 4 "Maximum positioning speed" 0..7999774 RW default=51200 unit=pps src=M:4 unverified=default
axis 5 "Maximum acceleration" 117..7629278 RW default=51200 unit=pps² src=M:4,M:7.6 unverified=default  # AMAX; velocity mode accelerates and decelerates with it
axis 6 "Maximum current" 0..255 RW default=128 src=M:4 unverified=default
axis 7 "Standby current" 0..255 RW default=8 src=M:4 unverified=default
axis 8 "Position reached flag" 0..1 R default=1 src=M:4
axis 9 "Home switch state" 0..1 R default=0 src=M:4
axis 10 "Right limit switch state" 0..1 R default=0 src=M:4
axis 11 "Left limit switch state" 0..1 R default=0 src=M:4
axis 12 "Right limit switch disable" 0..1 RW default=0 src=M:4 unverified=default
axis 13 "Left limit switch disable" 0..1 RW default=0 src=M:4 unverified=default
axis 14 "Swap limit switches" 0..1 RW default=0 src=M:4 unverified=default not-simulated="the two limit switches are not swapped"
axis 15 "Acceleration A1" 117..7629278 RW default=51200 unit=pps² src=M:4 unverified=default
axis 16 "Velocity V1" 0..1000000 RW default=0 unit=pps src=M:4,M:7.6 unverified=default  # 0: no EightPoint ramp, AMAX and DMAX alone (7.6)
axis 17 "Maximum deceleration" 117..7629278 RW default=51200 unit=pps² src=M:4,M:7.6 unverified=default  # DMAX: from VMAX to V2 (7.6; the row says "to V1", errata)
axis 18 "Deceleration D1" 117..7629278 RW default=51200 unit=pps² src=M:4 unverified=default
axis 19 "Velocity VSTART" 0..249999 RW default=0 unit=pps src=M:4 unverified=default  # not above VSTOP
axis 20 "Velocity VSTOP" 0..249999 RW default=10 unit=pps src=M:4 unverified=default  # "do not set lower than 10"
axis 21 "Ramp wait time" 0..65535 RW default=0 unit="32 µs" src=M:4,M:7.6 unverified=default  # TZEROWAIT: rest after v = 0 before the next move
axis 22 "Speed threshold for CoolStep / fullstep" 0..7999774 RW default=0 unit=pps src=M:4 unverified=default
axis 23 "Minimum speed for DcStep" 0..7999774 RW default=0 unit=pps src=M:4 unverified=default
axis 24 "Right limit switch polarity" 0..1 RW default=0 src=M:4 unverified=default not-simulated="the right switch's polarity is not inverted"
axis 25 "Left limit switch polarity" 0..1 RW default=0 src=M:4 unverified=default not-simulated="the left switch's polarity is not inverted"
axis 26 "Soft stop enable" 0..1 RW default=0 src=M:4 unverified=default  # limit switches; the virtual stops too (errata)
axis 27 "High speed chopper mode" 0..1 RW default=0 src=M:4 unverified=default
axis 28 "High speed fullstep mode" 0..1 RW default=0 src=M:4 unverified=default
axis 29 "Measured speed" 0..7999774 R default=0 unit=pps src=M:4 not-simulated="reads 0 while the motor turns: the measured speed is not computed"
axis 31 "Power down ramp" 0..15 RW default=0 unit="0.16384 s" src=M:4 unverified=default
axis 32 "DcStep time" 0..1023 RW default=0 src=M:4 unverified=default
axis 33 "DcStep StallGuard" 0..255 RW default=0 src=M:4 unverified=default
axis 34 "Acceleration A2" 117..7629278 RW default=51200 unit=pps² src=M:4,M:7.6 unverified=default  # from V1 to V2
axis 35 "Velocity V2" 0..1000000 RW default=0 unit=pps src=M:4,M:7.6 unverified=default  # table 24 calls it "Acceleration V2"; 0 (or <= V1): no A2/D2 phase
axis 36 "Deceleration D2" 117..7629278 RW default=51200 unit=pps² src=M:4,M:7.6 unverified=default  # from V2 to V1
axis 37 "Waiting time at VMAX" 0..65535 RW default=0 src=M:4,M:1.3 unverified=default,unit not-simulated="the ramp keeps no minimum cruise time: VMAX is not lowered to make room for one"  # TVMAX; the table gives no unit
axis 38 "Virtual stop left position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:4 unverified=default  # "Virtual stop left": named apart from the USB-2-SD's 26 (errata M51)
axis 39 "Virtual stop right position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:4 unverified=default  # "Virtual stop right"
axis 40 "Virtual stop flags" 0..2 R default=0 src=M:4  # 0 none, 1 at the left, 2 at the right virtual stop
axis 41 "Virtual stops enabled" 0..3 RW default=0 src=M:4 unverified=default  # "Virtual stop enable": bit 0 left, bit 1 right
axis 42 "Virtual stop encoder mode" 0..1 RW default=0 src=M:4 unverified=default not-simulated="the virtual stops compare the actual position (1), never the encoder position"
axis 43 "Compare position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:4 unverified=default not-simulated="no position compare is modelled: no compare output pulse, no interrupt 9"
axis 44 "Compare repeat" 0..16777215 RW default=0 unit=μsteps src=M:4 unverified=default not-simulated="no position compare is modelled: no compare output pulse, no interrupt 9"
axis 45 "Position compare output mask" 0..7 RW default=0 src=M:4 unverified=default not-simulated="no position compare is modelled: no output becomes a compare output"
axis 46 "Position compare pulse length" 0..255 RW default=0 unit=ms src=M:4 unverified=default not-simulated="no position compare is modelled: no compare output pulse"
axis 47 "Target reached output mask" 0..7 RW default=0 src=M:4 unverified=default not-simulated="no output follows the target reached state"
axis 48 "Motion start input mask" 0..7 RW default=0 src=M:4 unverified=default not-simulated="motions start at once: no input holds them back"
axis 127 "Relative positioning option" 0..1 RW default=0 src=M:4 unverified=default  # 0: from the last target position
axis 140 "Microstep resolution" 0..8 RW default=8 src=M:4,M:7.5  # 7.5: "default setting is 256 microsteps per full step"
axis 160 "Step interpolation enable" 0..1 RW default=0 src=M:4 unverified=default
axis 162 "Chopper blank time" 0..3 RW default=2 src=M:4 unverified=default
axis 163 "Constant TOff mode" 0..1 RW default=0 src=M:4 unverified=default
axis 164 "Disable fast decay comparator" 0..1 RW default=0 src=M:4 unverified=default  # the table spells it "comperator"
axis 165 "Chopper hysteresis end / fast decay time" 0..15 RW default=0 src=M:4 unverified=default
axis 166 "Chopper hysteresis start / sine wave offset" 0..8 RW default=0 src=M:4 unverified=default
axis 167 "Chopper off time (TOff)" 0..15 RW default=5 src=M:4 unverified=default
axis 168 "SmartEnergy current minimum (SEIMIN)" 0..1 RW default=0 src=M:4 unverified=default
axis 169 "SmartEnergy current down step" 0..3 RW default=0 src=M:4 unverified=default
axis 170 "SmartEnergy hysteresis" 0..15 RW default=0 src=M:4 unverified=default
axis 171 "SmartEnergy current up step" 0..3 RW default=0 src=M:4 unverified=default
axis 172 "SmartEnergy hysteresis start" 0..15 RW default=0 src=M:4  # "setting this to 0 (default) turns off CoolStep"
axis 173 "StallGuard2 filter enable" 0..1 RW default=0 src=M:4 unverified=default
axis 174 "StallGuard2 threshold" -64..63 RW default=0 src=M:4  # "zero is the starting value"
axis 178 "Global scaler" 0..255 RW default=0 src=M:4 unverified=default  # 0 full scale, 1..31 not to be used
axis 179 "Full scale current range" 0..3 RW default=0 src=M:4 unverified=default
axis 180 "SmartEnergy actual current" 0..31 R default=0 src=M:4
axis 181 "Stop on stall" 0..7999774 RW default=0 unit=pps src=M:4 unverified=default
axis 182 "SmartEnergy threshold speed" 0..7999774 RW default=0 unit=pps src=M:4 unverified=default
axis 185 "Passive fast decay time" 0..15 RW default=0 src=M:4 unverified=default
axis 186 "PWM threshold speed" 0..7999774 RW default=0 unit=pps src=M:4 unverified=default
axis 187 "PWM gradient" 0..15 RW default=0 src=M:4 unverified=default  # 0: StealthChop off
axis 188 "PWM amplitude" 0..255 RW default=128 src=M:4 unverified=default
axis 189 "PWM scale" 0..255 R default=0 src=M:4 not-simulated="reads 0: not modelled"
axis 190 "PWM mode" 0..1 R default=0 src=M:4 not-simulated="reads 0: not modelled"
axis 191 "PWM frequency" 0..3 RW default=0 src=M:4 unverified=default
axis 192 "PWM autoscale" 0..1 RW default=1 src=M:4 unverified=default
axis 193 "Reference search mode" 1..136 RW default=1 values=1..10,65..68,133..136 src=M:4,M:7.1 unverified=default  # 1..10 (table 22); +64: the right switch (1..4); +128: inverted home switch (5..8); 9, 10 the encoder's null channel
axis 194 "Reference search speed" 0..7999774 RW default=51200 unit=pps src=M:4 unverified=default
axis 195 "Reference switch speed" 0..7999774 RW default=5120 unit=pps src=M:4 unverified=default
axis 196 "End switch distance" -2147483648..2147483647 R default=0 unit=μsteps src=M:4
axis 197 "Last reference position" -2147483648..2147483647 R default=0 unit=μsteps src=M:4
axis 201 "Encoder mode" 0..511 RW default=0 src=M:4,M:7.2 unverified=default not-simulated="no null channel is modelled: the encoder is never cleared or latched by it"
axis 202 "Motor fullstep resolution" 0..32768 RW default=200 unit=fullsteps/round src=M:4,M:7.2  # "the default value is 200"
axis 204 "Freewheeling mode" 0..3 RW default=0 src=M:4 unverified=default
axis 206 "Actual load value" 0..1023 R default=0 src=M:4
axis 207 "Extended error flags" 0..3 R default=0 src=M:4
axis 208 "Motor driver error flags" 0..255 R default=0 src=M:4
axis 209 "Encoder position" -2147483648..2147483647 RW default=0 unit=μsteps src=M:4,M:7.2  # converted to microsteps (7.2)
axis 210 "Encoder resolution" -2147483648..2147483647 RW default=0 src=M:4,M:7.2 unverified=default not-simulated="209 counts the shaft in microsteps whatever the resolution says (as when 202 and 210 are set right, 7.2); a negative value does not reverse it"  # counts per round (cpr)
axis 212 "Maximum encoder deviation" 0..2147483647 RW default=0 unit="encoder steps" src=M:4 unverified=default  # 0: off
axis 214 "Power down delay" 0..417 RW default=0 unit="10 ms" src=M:4  # "the standard value is 0"
axis 251 "Reverse shaft" 0..1 RW default=0 src=M:4 unverified=default not-simulated="the motor's direction is not reversed (a placed switch would be met from the other side)"
axis 220 "StallGuard4 result" 0..510 R default=0 src=P unverified=range,access not-simulated="StallGuard4 is not modelled: the module's load value is stallGuard2's (206)"  # PyTrinamic only, not in table 16
axis 221 "StallGuard4 threshold" 0..255 RW default=0 src=P unverified=range,access,default not-simulated="StallGuard4 is not modelled: stall detection uses stallGuard2's threshold (174)"
axis 222 "StallGuard4 filter enable" 0..1 RW default=0 src=P unverified=range,access,default not-simulated="StallGuard4 is not modelled"
axis 223 "StallGuard4 angle offset" 0..1 RW default=0 src=P unverified=range,access,default not-simulated="StallGuard4 is not modelled"
axis 255 "Unit mode" 0..1 RW default=1 src=M:7.5 unverified=exists,range,access not-simulated="values are pps whatever it says"  # 7.5: "which is also the default value"; table 16 lacks the row

# Global parameters, bank 0 (table 18). Numbers 64..127 are stored in the EEPROM at every SGP
# (5.1): access A. The conversion merged the rows of 65, 66 and 68 (errata).
global 0 65 "RS485 baud rate" 0..11 RWA default=0 src=M:5.1 unverified=default  # 0 = 9600 ... 11 = 1000000 baud
global 0 66 "Serial address" 1..255 RWA default=1 src=M:5.1 unverified=default
global 0 68 "Serial heartbeat" 0..65535 RWA default=0 unit=ms src=M:5.1 not-simulated="no heartbeat supervision"  # 0 (default): off
global 0 76 "Serial host address" 0..255 RWA default=2 src=M:5.1 unverified=default
global 0 77 "Auto start mode" 0..1 RWA default=0 src=M:5.1  # 0 (default)
global 0 78 "I/O mode" 0..7 RWA default=0 src=M:5.1,M:6.3 unverified=default not-simulated="the GPIOs are inputs (bank 0) and outputs (bank 2) at once whatever the mode says"  # a bit per GPIO: 1 output
global 0 81 "TMCL code protection" 0..3 RWA default=0 src=M:5.1 unverified=default not-simulated="program memory is not protected"
global 0 84 "Coordinate storage" 0..1 RWA default=0 src=M:5.1,M:3.6.22  # 'with the default setting, the coordinates are stored in RAM only'
global 0 85 "Do not restore user variables" 0..1 RWA default=0 src=M:5.1  # 0 (default)
global 0 87 "Serial secondary address" 0..255 RWA default=0 src=M:5.1,M:7.9 unverified=default not-simulated="the virtual module answers only its address"  # 0: off
global 0 128 "TMCL application status" 0..3 R default=0 src=M:5.1
global 0 129 "Download mode" 0..1 R default=0 src=M:5.1
global 0 130 "TMCL program counter" 0..2047 R default=0 src=M:5.1 unverified=range  # no range in the table: that of the program memory
global 0 132 "TMCL tick timer" 0..2147483647 RW default=0 unit=ms src=M:5.1
global 0 133 "Random number" 0..2147483647 RW default=0 src=M:5.1
global 0 255 "Suppress reply" 0..1 RW default=0 src=M:5.1  # "reset to 0 on startup"

# Interrupt configuration, bank 3 (table 20).
global 3 0 "Timer 0 period" 0..4294967295 RW default=0 unit=ms src=M:5.4
global 3 1 "Timer 1 period" 0..4294967295 RW default=0 unit=ms src=M:5.4
global 3 2 "Timer 2 period" 0..4294967295 RW default=0 unit=ms src=M:5.4
global 3 27 "Left stop switch 0 trigger transition" 0..3 RW default=0 src=M:5.4  # 0 off, 1 low-high, 2 high-low, 3 both
global 3 28 "Right stop switch 0 trigger transition" 0..3 RW default=0 src=M:5.4
global 3 39 "Input 0 trigger transition" 0..3 RW default=0 src=M:5.4
global 3 40 "Input 1 trigger transition" 0..3 RW default=0 src=M:5.4
global 3 41 "Input 2 trigger transition" 0..3 RW default=0 src=M:5.4

# I/O ports: the GIO/SIO tables of sections 3.6.12 and 3.6.13. GIO 255, 0 reads the inputs as a
# bit vector, SIO 255, 2 sets the outputs; SIO 0, 0 sets the pull-up resistors of GPIO0..2 (a
# bit each). The manual gives the supply voltage (1/10 V) and temperature (°C) by unit only:
# their ranges and the values they read until a scenario sets them (24 V, 25 °C) are ours.
port 0 0 "GPIO0" in digital src=M:3.6.13
port 0 1 "GPIO1" in digital src=M:3.6.13
port 0 2 "GPIO2" in digital src=M:3.6.13
port 0 255 "All digital inputs" in bits 0..7 src=M:3.6.13
port 0 0 "Pull-up resistors" out analog 0..7 default=0 src=M:3.6.12 unverified  # a bit per GPIO; the default is ours
port 1 0 "AIN0" in analog 0..4095 src=M:3.6.13
port 1 8 "Supply voltage" in analog 0..1000 default=240 unit="0.1 V" src=M:3.6.13 unverified
port 1 9 "Temperature" in analog -40..150 default=25 unit="°C" src=M:3.6.13 unverified
port 2 0 "GPIO0" out digital src=M:3.6.12
port 2 1 "GPIO1" out digital src=M:3.6.12
port 2 2 "GPIO2" out digital src=M:3.6.12
port 2 255 "All outputs" out bits 0..7 src=M:3.6.12

# Interrupt vectors (table 12; the TI_ names of Interrupts.inc).
vector 0 TI_TIMER0 "Timer 0" src=M:table12
vector 1 TI_TIMER1 "Timer 1" src=M:table12
vector 2 TI_TIMER2 "Timer 2" src=M:table12
vector 3 TI_TARGET0 "Target position reached, axis 0" src=M:table12
vector 9 TI_POSCMP0 "Position compare, axis 0" src=M:table12
vector 15 TI_STALL0 "stallGuard, axis 0" src=M:table12
vector 21 TI_DEVIATION0 "Deviation, axis 0" src=M:table12
vector 27 TI_STOPL0 "Left stop switch, axis 0" src=M:table12
vector 28 TI_STOPR0 "Right stop switch, axis 0" src=M:table12
vector 39 TI_INPUT0 "Input change 0" src=M:table12
vector 40 TI_INPUT1 "Input change 1" src=M:table12
vector 41 TI_INPUT2 "Input change 2" src=M:table12
vector 255 TI_GLOBAL "Global interrupt enable" src=M:table12
