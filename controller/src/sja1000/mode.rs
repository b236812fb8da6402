//! [`ModeControl`]: the mode register MOD: reset mode (RM), listen-only
//! (LOM), self test (STM), acceptance filter mode (AFM) and sleep (SM); see
//! "Reset mode" and "Sleep" in the module documentation of [`super`].
//!
//! In reset mode a write sets LOM, STM and AFM, and RM = 0 enters operating
//! mode (starting the bus-off recovery, `recover`, if the core is held in
//! bus-off). In operating mode a write with RM = 1 enters reset mode; SM = 1
//! sleeps if no interrupt is pending, the bus is idle and no transmission
//! is pending (otherwise SM stays 0); SM = 0 wakes the node (WUI). A
//! dominant bit on the bus wakes it too, and so does entering reset mode,
//! which a bus-off also causes (`busoff`). `enter_rm` tells the other
//! blocks.
//!
//! State: `opm` (operating mode, = !RM), `lom`, `stm`, `afm`, `sleep`; all
//! cleared by `rst` (so RM = 1 after a hardware reset).

use super::regs;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ModeControl {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    /// A host write of MOD, with the data.
    pub wr: Signal<In, Bit>,
    pub wdata: Signal<In, Bits<8>>,
    /// Sleep is allowed: no interrupt pending, bus idle, no transmission pending.
    pub may_sleep: Signal<In, Bit>,
    /// A dominant bit was sampled on the bus.
    pub bus_dom: Signal<In, Bit>,
    /// The core went bus-off; the core is held in bus-off (bus-off hold).
    pub busoff: Signal<In, Bit>,
    pub hold: Signal<In, Bit>,

    pub opm: Signal<Out, Bit>,
    pub lom: Signal<Out, Bit>,
    pub stm: Signal<Out, Bit>,
    pub afm: Signal<Out, Bit>,
    pub sleep: Signal<Out, Bit>,
    /// MOD as read.
    pub rdata: Signal<Out, Bits<8>>,
    pub enter_rm: Signal<Out, Bit>,
    pub recover: Signal<Out, Bit>,
    /// Wake-up (WUI).
    pub wui: Signal<Out, Bit>,

    opm_r: DFF<Bit>,
    lom_r: DFF<Bit>,
    stm_r: DFF<Bit>,
    afm_r: DFF<Bit>,
    sleep_r: DFF<Bit>,
    // bit positions in MOD (from the register table)
    b_rm: Constant<Bits<3>>,
    b_lom: Constant<Bits<3>>,
    b_stm: Constant<Bits<3>>,
    b_afm: Constant<Bits<3>>,
    b_sm: Constant<Bits<3>>,

    l_rd: Signal<Local, Bits<8>>,
    l_rm: Signal<Local, Bit>,
}

fn pos(mask: u8) -> Constant<Bits<3>> {
    Constant::new((regs::pos(mask) as u64).into())
}

impl Default for ModeControl {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            wr: Default::default(),
            wdata: Default::default(),
            may_sleep: Default::default(),
            bus_dom: Default::default(),
            busoff: Default::default(),
            hold: Default::default(),
            opm: Default::default(),
            lom: Default::default(),
            stm: Default::default(),
            afm: Default::default(),
            sleep: Default::default(),
            rdata: Default::default(),
            enter_rm: Default::default(),
            recover: Default::default(),
            wui: Default::default(),
            opm_r: Default::default(),
            lom_r: Default::default(),
            stm_r: Default::default(),
            afm_r: Default::default(),
            sleep_r: Default::default(),
            b_rm: pos(regs::MOD_RM),
            b_lom: pos(regs::MOD_LOM),
            b_stm: pos(regs::MOD_STM),
            b_afm: pos(regs::MOD_AFM),
            b_sm: pos(regs::MOD_SM),
            l_rd: Default::default(),
            l_rm: Default::default(),
        }
    }
}

impl Logic for ModeControl {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, opm_r, lom_r, stm_r, afm_r, sleep_r);
        self.enter_rm.next = false;
        self.recover.next = false;
        self.wui.next = false;
        if self.wr.val() {
            if !self.opm_r.q.val() {
                self.lom_r.d.next = self.wdata.val().get_bit(self.b_lom.val().index());
                self.stm_r.d.next = self.wdata.val().get_bit(self.b_stm.val().index());
                self.afm_r.d.next = self.wdata.val().get_bit(self.b_afm.val().index());
                if !self.wdata.val().get_bit(self.b_rm.val().index()) {
                    self.opm_r.d.next = true;
                    self.recover.next = self.hold.val();
                }
            } else if self.wdata.val().get_bit(self.b_rm.val().index()) {
                self.enter_rm.next = true;
            } else if self.wdata.val().get_bit(self.b_sm.val().index()) {
                if !self.sleep_r.q.val() & self.may_sleep.val() {
                    self.sleep_r.d.next = true;
                }
            } else if self.sleep_r.q.val() {
                self.sleep_r.d.next = false;
                self.wui.next = true;
            }
        }
        if self.sleep_r.q.val() & self.bus_dom.val() {
            self.sleep_r.d.next = false;
            self.wui.next = true;
        }
        if self.busoff.val() {
            self.enter_rm.next = true;
        }
        if self.enter_rm.val() {
            self.opm_r.d.next = false;
            self.sleep_r.d.next = false;
            if self.sleep_r.q.val() {
                self.wui.next = true;
            }
        }
        if self.rst.val() {
            self.opm_r.d.next = false;
            self.lom_r.d.next = false;
            self.stm_r.d.next = false;
            self.afm_r.d.next = false;
            self.sleep_r.d.next = false;
        }

        // (RM through a 1-bit signal: Verilog would widen `~opm` in the shift)
        self.l_rm.next = !self.opm_r.q.val();
        self.l_rd.next = 0.into();
        self.l_rd.next = self.l_rd.val().replace_bit(self.b_rm.val().index(), self.l_rm.val());
        self.l_rd.next = self.l_rd.val().replace_bit(self.b_lom.val().index(), self.lom_r.q.val());
        self.l_rd.next = self.l_rd.val().replace_bit(self.b_stm.val().index(), self.stm_r.q.val());
        self.l_rd.next = self.l_rd.val().replace_bit(self.b_afm.val().index(), self.afm_r.q.val());
        self.l_rd.next = self.l_rd.val().replace_bit(self.b_sm.val().index(), self.sleep_r.q.val());
        self.rdata.next = self.l_rd.val();
        self.opm.next = self.opm_r.q.val();
        self.lom.next = self.lom_r.q.val();
        self.stm.next = self.stm_r.q.val();
        self.afm.next = self.afm_r.q.val();
        self.sleep.next = self.sleep_r.q.val();
    }
}

canstar_hdl::impl_clocked!(ModeControl);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn write(u: &mut ModeControl, v: u8) -> bool {
        u.wr.next = true;
        u.wdata.next = (v as u64).into();
        drive::settle(u);
        let wui = u.wui.val();
        drive::cycle(u);
        u.wr.next = false;
        drive::cycle(u);
        wui
    }

    fn rd(u: &ModeControl) -> u8 {
        u.rdata.val().index() as u8
    }

    #[test]
    fn reset_mode_operating_mode_and_sleep() {
        let mut u = ModeControl::default();
        drive::init(&mut u);
        u.rst.next = true;
        drive::cycle(&mut u);
        u.rst.next = false;
        assert_eq!(rd(&u), regs::MOD_RM, "reset mode after a hardware reset");
        // LOM, STM, AFM are set in reset mode; RM = 0 leaves it
        write(&mut u, regs::MOD_LOM | regs::MOD_AFM | regs::MOD_RM);
        assert_eq!(rd(&u), regs::MOD_LOM | regs::MOD_AFM | regs::MOD_RM);
        write(&mut u, regs::MOD_STM);
        assert_eq!(rd(&u), regs::MOD_STM);
        // ... and are kept in operating mode
        write(&mut u, regs::MOD_LOM);
        assert_eq!(rd(&u), regs::MOD_STM);
        // sleep only when allowed; SM = 0 wakes (WUI)
        u.may_sleep.next = false;
        write(&mut u, regs::MOD_SM);
        assert_eq!(rd(&u) & regs::MOD_SM, 0);
        u.may_sleep.next = true;
        write(&mut u, regs::MOD_SM);
        assert_eq!(rd(&u) & regs::MOD_SM, regs::MOD_SM);
        assert!(write(&mut u, 0), "wake-up by the host");
        assert_eq!(rd(&u) & regs::MOD_SM, 0);
        // a dominant bus bit wakes too
        write(&mut u, regs::MOD_SM);
        u.bus_dom.next = true;
        drive::settle(&mut u);
        assert!(u.wui.val());
        drive::cycle(&mut u);
        u.bus_dom.next = false;
        assert_eq!(rd(&u) & regs::MOD_SM, 0);
        // a bus-off enters reset mode; leaving it with the hold asks for recovery
        u.busoff.next = true;
        drive::settle(&mut u);
        assert!(u.enter_rm.val());
        drive::cycle(&mut u);
        u.busoff.next = false;
        assert_eq!(rd(&u) & regs::MOD_RM, regs::MOD_RM);
        u.hold.next = true;
        u.wr.next = true;
        u.wdata.next = 0.into();
        drive::settle(&mut u);
        assert!(u.recover.val());
    }
}
