//! [`FaultConfinement`]: the error counters and the error state (can-protocol.md §13).
//!
//! On every `sample` the counters take the strobes of the bit: TEC +8
//! (`tinc`) or -1 (`tdec`, not below 0); while REC < 128: REC +8 (`rinc8`),
//! else +1 (`rinc1`), else -1 on a successful reception (`rok`, not below
//! 0); a successful reception with REC ≥ 128 sets REC to 127 (C11), and REC
//! saturates at 128..135 otherwise (C12: no increment at or above 128). In
//! listen-only mode the counters are frozen (as in the SJA1000).
//!
//! Bus-off: `busoff` is high while the bit being processed would take TEC
//! above 255 (bit 8 set) and the node is not in Bus_Off yet; the sequencer
//! then enters Bus_Off, and the recovery starts from 0 runs (not armed).
//! Recovery: the sequencer strobes `run` after each run of 11 recessive
//! bits in Bus_Off; the 128th run (`last_run`) clears both counters.
//! `armed` says a recovery may proceed when `host_recovery` is set: a
//! `recover` strobe was seen since the node went bus-off (the strobe on
//! the current clock counts).
//!
//! Counter load (`cnt_load`, every clock, priority over `reset` and the
//! protocol): TEC and REC take `tec_in` and `rec_in`; a load that puts
//! the node into or out of Bus_Off (`tec_in` ≥ 256, or the node is in
//! Bus_Off) restarts the recovery (0 runs, not armed).
//!
//! State: `tecr`, `recr` (the counters); `runr` (completed recovery runs
//! 0..127, cleared on entering Bus_Off and after recovery); `rarmed` (a
//! `recover` strobe was seen; set by the strobe on any clock, cleared on
//! entering Bus_Off and after recovery).

use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct FaultConfinement {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub listen_only: Signal<In, Bit>,
    pub recover: Signal<In, Bit>,
    pub tinc: Signal<In, Bit>,
    pub tdec: Signal<In, Bit>,
    pub rinc1: Signal<In, Bit>,
    pub rinc8: Signal<In, Bit>,
    pub rok: Signal<In, Bit>,
    /// A bus-off recovery run of 11 recessive bits completed at this bit.
    pub run: Signal<In, Bit>,
    /// The sequencer is in Bus_Off.
    pub in_busoff: Signal<In, Bit>,
    pub cnt_load: Signal<In, Bit>,
    pub tec_in: Signal<In, Bits<9>>,
    pub rec_in: Signal<In, Bits<8>>,

    pub tec: Signal<Out, Bits<9>>,
    pub rec: Signal<Out, Bits<8>>,
    /// 0 error-active, 1 error-passive, 2 bus-off.
    pub state: Signal<Out, Bits<2>>,
    pub err_warn: Signal<Out, Bit>,
    /// Error-active: TEC and REC below 128.
    pub active: Signal<Out, Bit>,
    /// Completed recovery runs.
    pub runs: Signal<Out, Bits<8>>,
    /// The next completed run is the 128th.
    pub last_run: Signal<Out, Bit>,
    pub armed: Signal<Out, Bit>,
    /// This bit takes the node to Bus_Off.
    pub busoff: Signal<Out, Bit>,

    tecr: DFF<Bits<9>>,
    recr: DFF<Bits<8>>,
    runr: DFF<Bits<8>>,
    rarmed: DFF<Bit>,

    l_tec: Signal<Local, Bits<9>>,
    l_rec: Signal<Local, Bits<8>>,
    l_clear: Signal<Local, Bit>,
    l_ge256: Signal<Local, Bit>,
    l_ge257: Signal<Local, Bit>,
    l_ge248: Signal<Local, Bit>,
    l_over: Signal<Local, Bit>,
    l_t128: Signal<Local, Bit>,
    l_r128: Signal<Local, Bit>,
}

impl Logic for FaultConfinement {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, tecr, recr, runr, rarmed);
        // TEC ≥ 128 and REC ≥ 128 (see the thresholds below).
        self.l_t128.next = self.tecr.q.val().get_bit(8) | self.tecr.q.val().get_bit(7);
        self.l_r128.next = self.recr.q.val().get_bit(7);
        // Recovery complete: the 128th run.
        self.l_clear.next = self.run.val() & (self.runr.q.val() == 127);
        self.l_tec.next = self.tecr.q.val();
        self.l_rec.next = self.recr.q.val();
        // Counted on `sample` only (frozen in listen-only mode).
        if self.sample.val() & !self.listen_only.val() {
            if self.l_clear.val() {
                self.l_tec.next = 0.into();
                self.l_rec.next = 0.into();
            } else {
                if self.tinc.val() {
                    self.l_tec.next = self.tecr.q.val() + 8;
                } else if self.tdec.val() & (self.tecr.q.val() != 0) {
                    self.l_tec.next = self.tecr.q.val() - 1;
                }
                if !self.l_r128.val() {
                    if self.rinc8.val() {
                        self.l_rec.next = self.recr.q.val() + 8;
                    } else if self.rinc1.val() {
                        self.l_rec.next = self.recr.q.val() + 1;
                    } else if self.rok.val() & (self.recr.q.val() != 0) {
                        self.l_rec.next = self.recr.q.val() - 1;
                    }
                } else if self.rok.val() {
                    self.l_rec.next = 127.into();
                }
            }
        }
        // Bus-off: `l_tec` ≥ 256 from TEC's bits beside the adders (issue
        // #16), so that the test does not wait for them: TEC + 8 ≥ 256 (9-bit
        // sum) for TEC in 248..=503, TEC − 1 ≥ 256 for TEC ≥ 257, TEC ≥ 256
        // otherwise. `l_ge248` is TEC in
        // 248..=503: bit 8 differs from "bits 7..3 all set".
        self.l_ge256.next = self.tecr.q.val().get_bit(8);
        self.l_ge257.next = self.tecr.q.val().get_bit(8) & (self.tecr.q.val().get_bits::<8>(0) != 0);
        self.l_ge248.next = self.tecr.q.val().get_bit(8) ^ (self.tecr.q.val().get_bits::<5>(3) == 31);
        // (A completed recovery, `l_clear`, comes in Bus_Off only, where
        // `busoff` is 0 anyway.)
        self.l_over.next = self.l_ge256.val();
        if self.sample.val() & !self.listen_only.val() {
            if self.tinc.val() {
                self.l_over.next = self.l_ge248.val();
            } else if self.tdec.val() {
                self.l_over.next = self.l_ge257.val();
            }
        }
        self.busoff.next = self.sample.val() & self.l_over.val() & !self.in_busoff.val();

        self.rarmed.d.next = self.rarmed.q.val() | self.recover.val();
        if self.sample.val() {
            self.tecr.d.next = self.l_tec.val();
            self.recr.d.next = self.l_rec.val();
            if self.run.val() {
                self.runr.d.next = self.runr.q.val() + 1;
            }
            if self.l_clear.val() | self.busoff.val() {
                self.runr.d.next = 0.into();
                self.rarmed.d.next = false;
            }
        }
        if self.reset.val() {
            self.tecr.d.next = 0.into();
            self.recr.d.next = 0.into();
            self.runr.d.next = 0.into();
            self.rarmed.d.next = false;
        }
        if self.cnt_load.val() {
            self.tecr.d.next = self.tec_in.val();
            self.recr.d.next = self.rec_in.val();
            if (self.tec_in.val() >= 256) | self.in_busoff.val() {
                self.runr.d.next = 0.into();
                self.rarmed.d.next = false;
            }
        }

        self.tec.next = self.tecr.q.val();
        self.rec.next = self.recr.q.val();
        // The thresholds as logic on the counters' bits (issue #16; Yosys
        // maps the comparisons to carry chains): TEC ≥ 256 is bit 8, ≥ 128
        // bit 8 or 7, ≥ 96 bit 8 or 7 or bits 6 and 5 (REC alike, 8 bits).
        self.state.next = 0.into();
        if self.tecr.q.val().get_bit(8) {
            self.state.next = 2.into();
        } else if self.l_t128.val() | self.l_r128.val() {
            self.state.next = 1.into();
        }
        self.err_warn.next = self.l_t128.val()
            | self.l_r128.val()
            | (self.tecr.q.val().get_bit(6) & self.tecr.q.val().get_bit(5))
            | (self.recr.q.val().get_bit(6) & self.recr.q.val().get_bit(5));
        self.active.next = !self.l_t128.val() & !self.l_r128.val();
        self.runs.next = self.runr.q.val();
        self.last_run.next = self.runr.q.val() == 127;
        self.armed.next = self.rarmed.q.val() | self.recover.val();
    }
}

canstar_hdl::impl_clocked!(FaultConfinement);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn block() -> FaultConfinement {
        let mut u = FaultConfinement::default();
        drive::init(&mut u);
        u.reset.next = true;
        drive::cycle(&mut u);
        u.reset.next = false;
        u
    }

    /// One processed bit with the strobes set by `f`, then a clock without `sample`.
    fn bit(u: &mut FaultConfinement, f: impl Fn(&mut FaultConfinement)) -> bool {
        u.sample.next = true;
        f(u);
        drive::settle(u);
        let busoff = u.busoff.val();
        drive::cycle(u);
        u.sample.next = false;
        for s in [&mut u.tinc, &mut u.tdec, &mut u.rinc1, &mut u.rinc8, &mut u.rok, &mut u.run] {
            s.next = false;
        }
        drive::cycle(u);
        busoff
    }

    fn counters(u: &FaultConfinement) -> (u64, u64, u64) {
        (u.tec.val().index() as u64, u.rec.val().index() as u64, u.state.val().index() as u64)
    }

    #[test]
    fn transmit_counter_warning_passive_and_bus_off() {
        let mut u = block();
        for _ in 0..12 {
            assert!(!bit(&mut u, |u| u.tinc.next = true));
        }
        assert_eq!(counters(&u), (96, 0, 0));
        assert!(u.err_warn.val() && u.active.val());
        for _ in 0..4 {
            bit(&mut u, |u| u.tinc.next = true);
        }
        assert_eq!(counters(&u), (128, 0, 1));
        assert!(!u.active.val());
        bit(&mut u, |u| u.tdec.next = true);
        assert_eq!(counters(&u), (127, 0, 0), "back to error-active");
        // 127 + 8k: 255 is still error-passive
        while u.tec.val().index() < 255 {
            assert!(!bit(&mut u, |u| u.tinc.next = true));
        }
        assert_eq!(counters(&u), (255, 0, 1));
        // the bit that takes TEC above 255 signals bus-off on its sample clock
        assert!(bit(&mut u, |u| u.tinc.next = true));
        assert_eq!(counters(&u), (263, 0, 2));
        // a bus-off node (in_busoff) does not signal it again
        u.in_busoff.next = true;
        assert!(!bit(&mut u, |_| {}));
    }

    /// Issue #16: the bus-off test from TEC's bits and the thresholds as bit
    /// logic equal the comparisons after the adders, for every TEC and REC.
    #[test]
    fn thresholds_from_bits_equal_the_comparisons() {
        let mut u = block();
        for tec in 0..512u64 {
            for rec in [0u64, 95, 96, 127, 128, 200, 255] {
                u.cnt_load.next = true;
                u.tec_in.next = tec.into();
                u.rec_in.next = rec.into();
                drive::cycle(&mut u);
                u.cnt_load.next = false;
                drive::settle(&mut u);
                let state = if tec >= 256 {
                    2
                } else if tec >= 128 || rec >= 128 {
                    1
                } else {
                    0
                };
                assert_eq!(counters(&u), (tec, rec, state), "tec {tec} rec {rec}");
                assert_eq!(u.err_warn.val(), tec >= 96 || rec >= 96, "tec {tec} rec {rec}");
                assert_eq!(u.active.val(), tec < 128 && rec < 128, "tec {tec} rec {rec}");
                for (tinc, tdec, lo) in [
                    (false, false, false),
                    (true, false, false),
                    (false, true, false),
                    (true, true, false),
                    (true, false, true),
                    (false, true, true),
                ] {
                    u.sample.next = true;
                    u.tinc.next = tinc;
                    u.tdec.next = tdec;
                    u.listen_only.next = lo;
                    drive::settle(&mut u);
                    let next = if lo {
                        tec
                    } else if tinc {
                        (tec + 8) % 512
                    } else if tdec && tec != 0 {
                        tec - 1
                    } else {
                        tec
                    };
                    assert_eq!(u.busoff.val(), next >= 256, "tec {tec} tinc {tinc} tdec {tdec} lo {lo}");
                }
                u.sample.next = false;
                u.tinc.next = false;
                u.tdec.next = false;
                u.listen_only.next = false;
                drive::settle(&mut u);
                assert!(!u.busoff.val());
            }
        }
    }

    #[test]
    fn receive_counter_saturation_and_restore() {
        let mut u = block();
        for _ in 0..15 {
            bit(&mut u, |u| u.rinc8.next = true);
        }
        bit(&mut u, |u| u.rinc1.next = true);
        assert_eq!(counters(&u).1, 121);
        bit(&mut u, |u| u.rinc8.next = true);
        assert_eq!(counters(&u).1, 129);
        // C12: no increment at or above 128; C11: a good reception restores 127
        bit(&mut u, |u| u.rinc8.next = true);
        bit(&mut u, |u| u.rinc1.next = true);
        assert_eq!(counters(&u), (0, 129, 1));
        bit(&mut u, |u| u.rok.next = true);
        assert_eq!(counters(&u), (0, 127, 0));
        bit(&mut u, |u| u.rok.next = true);
        assert_eq!(counters(&u).1, 126);
        // listen-only mode freezes both counters
        u.listen_only.next = true;
        bit(&mut u, |u| {
            u.tinc.next = true;
            u.rinc1.next = true
        });
        assert_eq!(counters(&u), (0, 126, 0));
    }

    #[test]
    fn recovery_runs_load_and_arming() {
        let mut u = block();
        // load a bus-off (priority over reset)
        u.cnt_load.next = true;
        u.reset.next = true;
        u.tec_in.next = 300.into();
        u.rec_in.next = 5.into();
        drive::cycle(&mut u);
        u.cnt_load.next = false;
        u.reset.next = false;
        u.in_busoff.next = true;
        assert_eq!(counters(&u), (300, 5, 2));
        assert!(!u.armed.val());
        u.recover.next = true;
        drive::cycle(&mut u);
        u.recover.next = false;
        drive::cycle(&mut u);
        assert!(u.armed.val(), "a recover strobe arms the recovery");
        for k in 0..128u64 {
            assert_eq!(u.runs.val().index() as u64, k);
            assert_eq!(u.last_run.val(), k == 127);
            bit(&mut u, |u| u.run.next = true);
        }
        assert_eq!(counters(&u), (0, 0, 0), "the 128th run clears the counters");
        assert_eq!(u.runs.val().index(), 0);
        assert!(!u.armed.val(), "and disarms");
    }
}
