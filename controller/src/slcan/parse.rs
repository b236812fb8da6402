//! [`LineParser`]: turns host characters into the fields of one command
//! line as they arrive, so that no line buffer is needed.
//!
//! State: `fresh` (the next character starts a line), `cmd` (the first
//! character), `pos` (characters before the CR, saturating at 31), `acc`
//! (hex digits of an identifier or of `sxxyy`, shifted in, 32 bits), `dlc`
//! (the DLC digit, or the `n` of `Sn`), `data` (data digits placed at their
//! position: byte 0 in bits 63..56), `bad` (a non-hex digit where one is
//! expected, a character after a single-character command, too many data
//! digits, or characters lost before it: the queue's bit 8).
//!
//! Per command (position 0 is the command): `t`/`r`: 1..3 identifier, 4
//! DLC, 5.. data; `T`/`R`: 1..8 identifier, 9 DLC, 10.. data; `s`: 1..4
//! BTR0 BTR1; `S`: 1 the rate digit; every other command takes no
//! argument. A CR ends the line (`fresh` = 1; the fields stay until the next
//! character is taken, for the engine to execute); an empty line has `pos` =
//! 0. LF is ignored. The length, the DLC range and the identifier range are
//! checked by the engine, which knows the command.
//! `rst` makes the parser wait for a new line.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct LineParser {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    /// Take `ch` (one clock per character).
    pub take: Signal<In, Bit>,
    /// A character; bit 8: characters were lost before it.
    pub ch: Signal<In, Bits<9>>,
    pub cmd: Signal<Out, Bits<8>>,
    pub len: Signal<Out, Bits<5>>,
    pub acc: Signal<Out, Bits<32>>,
    pub dlc: Signal<Out, Bits<4>>,
    pub data: Signal<Out, Bits<64>>,
    pub bad: Signal<Out, Bit>,

    fresh: DFF<Bit>,
    cmd_r: DFF<Bits<8>>,
    pos: DFF<Bits<5>>,
    acc_r: DFF<Bits<32>>,
    dlc_r: DFF<Bits<4>>,
    data_r: DFF<Bits<64>>,
    bad_r: DFF<Bit>,

    l_c: Signal<Local, Bits<8>>,
    l_hex: Signal<Local, Bit>,
    l_nib: Signal<Local, Bits<4>>,
    l_std: Signal<Local, Bit>,
    l_ext: Signal<Local, Bit>,
    l_q: Signal<Local, Bits<5>>,
    l_dat: Signal<Local, Bit>,
}

impl Default for LineParser {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            take: Default::default(),
            ch: Default::default(),
            cmd: Default::default(),
            len: Default::default(),
            acc: Default::default(),
            dlc: Default::default(),
            data: Default::default(),
            bad: Default::default(),
            fresh: Default::default(),
            cmd_r: Default::default(),
            pos: Default::default(),
            acc_r: Default::default(),
            dlc_r: Default::default(),
            data_r: Default::default(),
            bad_r: Default::default(),
            l_c: Default::default(),
            l_hex: Default::default(),
            l_nib: Default::default(),
            l_std: Default::default(),
            l_ext: Default::default(),
            l_q: Default::default(),
            l_dat: Default::default(),
        }
    }
}

impl Logic for LineParser {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, fresh, cmd_r, pos, acc_r, dlc_r, data_r, bad_r);
        self.l_c.next = self.ch.val().get_bits::<8>(0);
        // hex digit (either case)
        self.l_hex.next = false;
        self.l_nib.next = 0.into();
        if (self.l_c.val() >= 0x30) & (self.l_c.val() <= 0x39) {
            self.l_hex.next = true;
            self.l_nib.next = self.l_c.val().get_bits::<4>(0);
        }
        if (self.l_c.val() >= 0x41) & (self.l_c.val() <= 0x46) {
            self.l_hex.next = true;
            self.l_nib.next = self.l_c.val().get_bits::<4>(0) + 9;
        }
        if (self.l_c.val() >= 0x61) & (self.l_c.val() <= 0x66) {
            self.l_hex.next = true;
            self.l_nib.next = self.l_c.val().get_bits::<4>(0) + 9;
        }
        self.l_std.next = (self.cmd_r.q.val() == 0x74) | (self.cmd_r.q.val() == 0x72);
        self.l_ext.next = (self.cmd_r.q.val() == 0x54) | (self.cmd_r.q.val() == 0x52);
        // index of a data digit
        self.l_q.next = self.pos.q.val() - 5;
        if self.l_ext.val() {
            self.l_q.next = self.pos.q.val() - 10;
        }

        self.l_dat.next = false;
        if self.take.val() {
            if self.l_c.val() == 0x0D {
                self.fresh.d.next = true;
                if self.fresh.q.val() {
                    // an empty line
                    self.cmd_r.d.next = 0.into();
                    self.pos.d.next = 0.into();
                    self.bad_r.d.next = self.ch.val().get_bit(8);
                } else if self.ch.val().get_bit(8) {
                    self.bad_r.d.next = true;
                }
            } else if self.l_c.val() == 0x0A {
                if self.ch.val().get_bit(8) {
                    self.bad_r.d.next = true;
                }
            } else if self.fresh.q.val() {
                self.fresh.d.next = false;
                self.cmd_r.d.next = self.l_c.val();
                self.pos.d.next = 1.into();
                self.acc_r.d.next = 0.into();
                self.dlc_r.d.next = 0.into();
                self.data_r.d.next = 0.into();
                self.bad_r.d.next = self.ch.val().get_bit(8);
            } else {
                if self.pos.q.val() != 31 {
                    self.pos.d.next = self.pos.q.val() + 1;
                }
                if self.ch.val().get_bit(8) | !self.l_hex.val() {
                    self.bad_r.d.next = true;
                }
                if self.l_std.val() {
                    if self.pos.q.val() <= 3 {
                        self.acc_r.d.next = (self.acc_r.q.val() << 4) | bit_cast::<32, 4>(self.l_nib.val());
                    } else if self.pos.q.val() == 4 {
                        self.dlc_r.d.next = self.l_nib.val();
                    } else {
                        self.l_dat.next = true;
                    }
                } else if self.l_ext.val() {
                    if self.pos.q.val() <= 8 {
                        self.acc_r.d.next = (self.acc_r.q.val() << 4) | bit_cast::<32, 4>(self.l_nib.val());
                    } else if self.pos.q.val() == 9 {
                        self.dlc_r.d.next = self.l_nib.val();
                    } else {
                        self.l_dat.next = true;
                    }
                } else if self.cmd_r.q.val() == 0x73 {
                    // sxxyy
                    if self.pos.q.val() <= 4 {
                        self.acc_r.d.next = (self.acc_r.q.val() << 4) | bit_cast::<32, 4>(self.l_nib.val());
                    } else {
                        self.bad_r.d.next = true;
                    }
                } else if self.cmd_r.q.val() == 0x53 {
                    // Sn
                    if self.pos.q.val() == 1 {
                        self.dlc_r.d.next = self.l_nib.val();
                    } else {
                        self.bad_r.d.next = true;
                    }
                } else {
                    self.bad_r.d.next = true;
                }
                if self.l_dat.val() {
                    if self.l_q.val() < 16 {
                        self.data_r.d.next = self.data_r.q.val()
                            | (bit_cast::<64, 4>(self.l_nib.val()) << (bit_cast::<6, 4>(!self.l_q.val().get_bits::<4>(0)) << 2));
                    } else {
                        self.bad_r.d.next = true;
                    }
                }
            }
        }
        if self.rst.val() {
            self.fresh.d.next = true;
            self.cmd_r.d.next = 0.into();
            self.pos.d.next = 0.into();
            self.acc_r.d.next = 0.into();
            self.dlc_r.d.next = 0.into();
            self.data_r.d.next = 0.into();
            self.bad_r.d.next = false;
        }
        self.cmd.next = self.cmd_r.q.val();
        self.len.next = self.pos.q.val();
        self.acc.next = self.acc_r.q.val();
        self.dlc.next = self.dlc_r.q.val();
        self.data.next = self.data_r.q.val();
        self.bad.next = self.bad_r.q.val();
    }
}

canstar_hdl::impl_clocked!(LineParser);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    /// (cmd, len, acc, dlc, data, bad) after the line.
    fn parse(p: &mut LineParser, line: &[u16]) -> (u8, u64, u64, u64, u64, bool) {
        for &c in line {
            p.take.next = true;
            p.ch.next = (c as u64).into();
            drive::cycle(p);
        }
        p.take.next = false;
        drive::cycle(p);
        (
            p.cmd.val().index() as u8,
            p.len.val().index() as u64,
            p.acc.val().index() as u64,
            p.dlc.val().index() as u64,
            p.data.val().to_u64(),
            p.bad.val(),
        )
    }

    fn s(x: &str) -> Vec<u16> {
        x.bytes().map(|b| b as u16).collect()
    }

    #[test]
    fn fields_of_each_command() {
        let mut p = LineParser::default();
        drive::init(&mut p);
        p.rst.next = true;
        drive::cycle(&mut p);
        p.rst.next = false;
        assert_eq!(parse(&mut p, &s("t1233a1b2c3\r")), (b't', 11, 0x123, 3, 0xA1B2C3 << 40, false));
        assert_eq!(parse(&mut p, &s("T1ABCDEF08\n0102030405060708\r")), (b'T', 26, 0x1ABCDEF0, 8, 0x0102030405060708, false));
        assert_eq!(parse(&mut p, &s("r7FF5\r")), (b'r', 5, 0x7FF, 5, 0, false));
        assert_eq!(parse(&mut p, &s("s031c\r")), (b's', 5, 0x031C, 0, 0, false));
        assert_eq!(parse(&mut p, &s("S6\r")), (b'S', 2, 0, 6, 0, false));
        assert_eq!(parse(&mut p, &s("O\r")), (b'O', 1, 0, 0, 0, false));
        assert_eq!(parse(&mut p, &s("\r")), (0, 0, 0, 0, 0, false));
        // bad hex, an argument to a one-character command, a lost character
        assert!(parse(&mut p, &s("t12g0\r")).5);
        assert!(parse(&mut p, &s("Ox\r")).5);
        let mut l = s("t1230\r");
        l[2] |= 0x100;
        assert!(parse(&mut p, &l).5);
        // too long: 17 data digits
        let r = parse(&mut p, &s("t1238000102030405060708090A0B0C0D0E0F10\r"));
        assert!(r.5);
        assert_eq!(r.1, 31);
        // the next line is clean again
        assert_eq!(parse(&mut p, &s("F\r")), (b'F', 1, 0, 0, 0, false));
    }
}
