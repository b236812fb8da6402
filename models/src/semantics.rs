//! A rust-hdl design that exercises the operator semantics the compiler must
//! reproduce (widths, wrapping, shifts at and beyond the width, variable slices and
//! bit replacement, `Bits<N> + bool`, `LiteralType << Bits<M>`, the 16x16
//! multiplier, reductions, comparisons, casts up and down, values wider than 64 bits,
//! enum matches with and without a wildcard, loops, locals assigned several times,
//! a child with a combinational path from its input to its output, a register whose
//! input is another register). Its compiled model is checked against rust-hdl on
//! random stimulus like the real designs.

use rust_hdl::prelude::*;

#[derive(Copy, Clone, Debug, PartialEq, Eq, LogicState)]
pub enum Phase {
    Idle,
    Load,
    Shift,
    Check,
    Done,
}

/// A child with a combinational path (`y` from `a`) and a register.
#[derive(LogicBlock, Default)]
pub struct Child {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<8>>,
    pub y: Signal<Out, Bits<8>>,
    pub r: Signal<Out, Bits<8>>,
    acc: DFF<Bits<8>>,
}

impl Logic for Child {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, acc);
        self.acc.d.next = self.acc.q.val() + self.a.val();
        self.y.next = (self.a.val() ^ self.acc.q.val()) + 1;
        self.r.next = self.acc.q.val();
    }
}

#[derive(LogicBlock)]
pub struct Ops {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<13>>,
    pub b: Signal<In, Bits<13>>,
    pub s: Signal<In, Bits<5>>,
    pub x: Signal<In, Bits<16>>,
    pub y: Signal<In, Bits<16>>,
    pub w: Signal<In, Bits<100>>,
    pub f: Signal<In, Bit>,
    pub arith: Signal<Out, Bits<13>>,
    pub shifts: Signal<Out, Bits<13>>,
    pub lit_shift: Signal<Out, Bits<64>>,
    pub prod: Signal<Out, Bits<32>>,
    pub flags: Signal<Out, Bits<12>>,
    pub slices: Signal<Out, Bits<8>>,
    pub replaced: Signal<Out, Bits<13>>,
    pub wide: Signal<Out, Bits<100>>,
    pub wide_slice: Signal<Out, Bits<16>>,
    pub casts: Signal<Out, Bits<24>>,
    pub state: Signal<Out, Bits<3>>,
    pub looped: Signal<Out, Bits<8>>,
    pub child_y: Signal<Out, Bits<8>>,
    pub chain: Signal<Out, Bits<8>>,
    /// Reads an output of this block before the block assigns it (rust-hdl: the settled value).
    pub early: Signal<Out, Bits<8>>,
    /// Reads a child's input the block assigns (rust-hdl `In::val()`: the settled value).
    pub echo: Signal<Out, Bits<8>>,
    pub ph: DFF<Phase>,
    cnt: DFF<Bits<4>>,
    pipe1: DFF<Bits<8>>,
    pipe2: DFF<Bits<8>>,
    child: Child,
    k: Constant<Bits<13>>,
    l: Signal<Local, Bits<13>>,
    m: Signal<Local, Bits<8>>,
}

impl Default for Ops {
    fn default() -> Self {
        Ops {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            s: Default::default(),
            x: Default::default(),
            y: Default::default(),
            w: Default::default(),
            f: Default::default(),
            arith: Default::default(),
            shifts: Default::default(),
            lit_shift: Default::default(),
            prod: Default::default(),
            flags: Default::default(),
            slices: Default::default(),
            replaced: Default::default(),
            wide: Default::default(),
            wide_slice: Default::default(),
            casts: Default::default(),
            state: Default::default(),
            looped: Default::default(),
            child_y: Default::default(),
            chain: Default::default(),
            early: Default::default(),
            echo: Default::default(),
            ph: Default::default(),
            cnt: Default::default(),
            pipe1: Default::default(),
            pipe2: Default::default(),
            child: Default::default(),
            k: Constant::new(0x1234.into()),
            l: Default::default(),
            m: Default::default(),
        }
    }
}

// The operators are written as rust-hdl users write them (the precedence and the
// match on a bool are part of what is tested).
#[allow(clippy::precedence, clippy::match_bool, clippy::single_match)]
impl Logic for Ops {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, ph, cnt, pipe1, pipe2);
        // arithmetic wraps at 13 bits; a local assigned several times
        self.l.next = self.a.val() + self.b.val();
        self.l.next = self.l.val() - (self.b.val() << 2) + self.k.val();
        self.l.next = self.l.val() + self.f.val();
        self.arith.next = self.l.val() ^ (self.a.val() & !self.b.val()) | 7;
        // shifts by a variable amount, also at and beyond the width
        self.shifts.next = (self.a.val() << self.s.val()) ^ (self.b.val() >> self.s.val());
        self.lit_shift.next = 1 << self.s.val();
        self.prod.next = self.x.val() * self.y.val();
        // comparisons and reductions
        self.flags.next = 0.into();
        if self.a.val() < self.b.val() {
            self.flags.next = self.flags.val() | 1;
        }
        if self.a.val() >= self.k.val() {
            self.flags.next = self.flags.val() | 2;
        }
        if self.a.val().all() {
            self.flags.next = self.flags.val() | 4;
        }
        if self.b.val().any() {
            self.flags.next = self.flags.val() | 8;
        }
        if self.x.val().xor() {
            self.flags.next = self.flags.val() | 16;
        }
        if (self.a.val() == 0x1fff) | (self.s.val() > 12) {
            self.flags.next = self.flags.val() | 32;
        }
        if self.a.val().get_bit(self.s.val().index() & 7) && !self.f.val() {
            self.flags.next = self.flags.val() | 64;
        }
        if self.a.val() != self.b.val() {
            self.flags.next = self.flags.val() | 0x800;
        }
        // variable slices and bit replacement
        self.slices.next = self.a.val().get_bits::<8>(self.s.val().index() & 7) ^ self.b.val().get_bits::<8>(3);
        self.replaced.next = self.a.val().replace_bit(self.s.val().index() & 7, self.f.val()).replace_bit(0, !self.f.val());
        // values wider than 64 bits
        self.wide.next = (self.w.val() + self.w.val() << 3) ^ (self.w.val() >> self.s.val());
        self.wide_slice.next = self.w.val().get_bits::<16>((self.s.val().index() & 15) + 70);
        // casts up and down
        self.casts.next = bit_cast::<24, 13>(self.a.val()) + bit_cast::<24, 16>(self.x.val()) + bit_cast::<24, 8>(bit_cast::<8, 13>(self.b.val()));
        // an enum state machine with a match without wildcard
        self.ph.d.next = self.ph.q.val();
        self.cnt.d.next = self.cnt.q.val();
        match self.ph.q.val() {
            Phase::Idle => {
                if self.f.val() {
                    self.ph.d.next = Phase::Load;
                }
            }
            Phase::Load => {
                self.cnt.d.next = self.a.val().get_bits::<4>(0);
                self.ph.d.next = Phase::Shift;
            }
            Phase::Shift => {
                self.cnt.d.next = self.cnt.q.val() - 1;
                if self.cnt.q.val() == 0 {
                    self.ph.d.next = Phase::Check;
                }
            }
            Phase::Check => {
                self.ph.d.next = Phase::Done;
            }
            Phase::Done => {
                self.ph.d.next = Phase::Idle;
            }
        }
        // a match with a wildcard, and one on a bool
        self.state.next = 0.into();
        match self.ph.q.val() {
            Phase::Load => {
                self.state.next = 1.into();
            }
            Phase::Check => {
                self.state.next = 2.into();
            }
            _ => {
                self.state.next = 5.into();
            }
        }
        match self.f.val() {
            true => {
                self.state.next = self.state.val() | 2;
            }
            false => {}
        }
        self.early.next = self.looped.val() ^ 0x5a;
        // a loop
        self.m.next = 0.into();
        for i in 0..8 {
            if self.a.val().get_bit(i) {
                self.m.next = self.m.val() + 1;
            }
        }
        self.looped.next = self.m.val();
        // child with a combinational path, a register chain
        self.child.clock.next = self.clock.val();
        self.child.a.next = self.m.val() + self.a.val().get_bits::<8>(5);
        self.child_y.next = self.child.y.val() ^ self.child.r.val();
        self.echo.next = self.child.a.val();
        self.pipe1.d.next = self.child.y.val();
        self.pipe2.d.next = self.pipe1.q.val();
        self.chain.next = self.pipe2.q.val();
    }
}

canstar_hdl::impl_clocked!(Ops);
