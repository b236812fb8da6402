//! [`Interrupts`]: the interrupt enable (IER) and interrupt (IR) registers
//! and the INT output (see "Interrupts" in the module documentation of
//! [`super`]).
//!
//! Each event arrives on its own input and is placed at its IR position
//! (`Constant` fields from the register table); it is latched only if its
//! IER bit is set at the time of the event. RI is a level: RIE and a
//! message in the FIFO (`rbs`). A read of IR (`rd_ir`) clears the latched
//! bits. `int_n` is low while any bit of IR as read is set.
//!
//! State: `ier_r`, `ir_r` (IER; the latched interrupts, never RI); both
//! cleared by `rst`.

use super::regs;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct Interrupts {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    /// A host write of IER (with the data), a host read of IR.
    pub wr_ier: Signal<In, Bit>,
    pub wdata: Signal<In, Bits<8>>,
    pub rd_ir: Signal<In, Bit>,
    /// The receive FIFO holds a message (RI level).
    pub rbs: Signal<In, Bit>,
    /// Events.
    pub ti: Signal<In, Bit>,
    pub ei: Signal<In, Bit>,
    pub doi: Signal<In, Bit>,
    pub wui: Signal<In, Bit>,
    pub epi: Signal<In, Bit>,
    pub ali: Signal<In, Bit>,
    pub bei: Signal<In, Bit>,

    pub ier: Signal<Out, Bits<8>>,
    /// IR as read: the latched bits and RI.
    pub ir: Signal<Out, Bits<8>>,
    pub int_n: Signal<Out, Bit>,

    ier_r: DFF<Bits<8>>,
    ir_r: DFF<Bits<8>>,
    b_ri: Constant<Bits<3>>,
    b_ti: Constant<Bits<3>>,
    b_ei: Constant<Bits<3>>,
    b_doi: Constant<Bits<3>>,
    b_wui: Constant<Bits<3>>,
    b_epi: Constant<Bits<3>>,
    b_ali: Constant<Bits<3>>,
    b_bei: Constant<Bits<3>>,

    l_ev: Signal<Local, Bits<8>>,
}

fn pos(mask: u8) -> Constant<Bits<3>> {
    Constant::new((regs::pos(mask) as u64).into())
}

impl Default for Interrupts {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            wr_ier: Default::default(),
            wdata: Default::default(),
            rd_ir: Default::default(),
            rbs: Default::default(),
            ti: Default::default(),
            ei: Default::default(),
            doi: Default::default(),
            wui: Default::default(),
            epi: Default::default(),
            ali: Default::default(),
            bei: Default::default(),
            ier: Default::default(),
            ir: Default::default(),
            int_n: Default::default(),
            ier_r: Default::default(),
            ir_r: Default::default(),
            b_ri: pos(regs::IRQ_RI),
            b_ti: pos(regs::IRQ_TI),
            b_ei: pos(regs::IRQ_EI),
            b_doi: pos(regs::IRQ_DOI),
            b_wui: pos(regs::IRQ_WUI),
            b_epi: pos(regs::IRQ_EPI),
            b_ali: pos(regs::IRQ_ALI),
            b_bei: pos(regs::IRQ_BEI),
            l_ev: Default::default(),
        }
    }
}

impl Logic for Interrupts {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, ier_r, ir_r);
        if self.wr_ier.val() {
            self.ier_r.d.next = self.wdata.val();
        }
        self.l_ev.next = 0.into();
        self.l_ev.next = self.l_ev.val().replace_bit(self.b_ti.val().index(), self.ti.val());
        self.l_ev.next = self.l_ev.val().replace_bit(self.b_ei.val().index(), self.ei.val());
        self.l_ev.next = self.l_ev.val().replace_bit(self.b_doi.val().index(), self.doi.val());
        self.l_ev.next = self.l_ev.val().replace_bit(self.b_wui.val().index(), self.wui.val());
        self.l_ev.next = self.l_ev.val().replace_bit(self.b_epi.val().index(), self.epi.val());
        self.l_ev.next = self.l_ev.val().replace_bit(self.b_ali.val().index(), self.ali.val());
        self.l_ev.next = self.l_ev.val().replace_bit(self.b_bei.val().index(), self.bei.val());
        self.ir_r.d.next = self.ir_r.q.val() | (self.l_ev.val() & self.ier_r.q.val());
        if self.rd_ir.val() {
            self.ir_r.d.next = self.l_ev.val() & self.ier_r.q.val();
        }
        if self.rst.val() {
            self.ier_r.d.next = 0.into();
            self.ir_r.d.next = 0.into();
        }
        self.ier.next = self.ier_r.q.val();
        self.ir.next = self
            .ir_r
            .q
            .val()
            .replace_bit(self.b_ri.val().index(), self.ier_r.q.val().get_bit(self.b_ri.val().index()) & self.rbs.val());
        self.int_n.next = !(self.ir.val().any());
    }
}

canstar_hdl::impl_clocked!(Interrupts);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn ir(u: &Interrupts) -> u8 {
        u.ir.val().index() as u8
    }

    #[test]
    fn enabled_events_latch_until_read_ri_is_a_level() {
        let mut u = Interrupts::default();
        drive::init(&mut u);
        u.rst.next = true;
        drive::cycle(&mut u);
        u.rst.next = false;
        u.wr_ier.next = true;
        u.wdata.next = ((regs::IRQ_TI | regs::IRQ_BEI | regs::IRQ_RI) as u64).into();
        drive::cycle(&mut u);
        u.wr_ier.next = false;
        // a disabled event is not latched, an enabled one is
        u.ei.next = true;
        u.ti.next = true;
        drive::cycle(&mut u);
        u.ei.next = false;
        u.ti.next = false;
        drive::cycle(&mut u);
        assert_eq!(ir(&u), regs::IRQ_TI);
        assert!(!u.int_n.val());
        u.bei.next = true;
        drive::cycle(&mut u);
        u.bei.next = false;
        u.rbs.next = true;
        drive::cycle(&mut u);
        assert_eq!(ir(&u), regs::IRQ_TI | regs::IRQ_BEI | regs::IRQ_RI);
        // a read clears the latched bits; RI stays while a message is held
        u.rd_ir.next = true;
        drive::cycle(&mut u);
        u.rd_ir.next = false;
        drive::cycle(&mut u);
        assert_eq!(ir(&u), regs::IRQ_RI);
        u.rbs.next = false;
        drive::settle(&mut u);
        assert_eq!(ir(&u), 0);
        assert!(u.int_n.val());
    }
}
