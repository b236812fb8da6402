//! [`CoreSim`]: the CAN controller core ([`canstar_controller::core::CanCore`]) on
//! either engine behind one interface: inputs as plain fields ([`CoreInputs`]),
//! outputs through [`CoreView`], one [`CoreSim::cycle`] per clock, the same probe
//! walk (VCD) on both.

use std::cell::RefCell;
use std::collections::HashMap;

use canstar_controller::core::CanCore as HdlCore;
use canstar_controller::core::RecRule;
use canstar_controller::view::CoreView;
use canstar_hdl::drive;
use rust_hdl::prelude::*;

use crate::engine::{fallback_warning, Engine};
use crate::generated::can_core::CanCore as ModelCore;
use crate::stim::Stim;
use crate::Model;

/// The core's inputs (names of [`HdlCore`]'s ports; register encodings, i.e. the
/// timing fields are value - 1). Applied to the engine on every [`CoreSim::cycle`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CoreInputs {
    pub reset: bool,
    pub rx: bool,
    pub brp: u8,
    pub prop: u8,
    pub ph1: u8,
    pub ph2: u8,
    pub sjw: u8,
    pub triple: bool,
    pub listen_only: bool,
    pub self_test: bool,
    pub single_shot: bool,
    pub host_recovery: bool,
    pub recover: bool,
    pub tx_req: bool,
    pub tx_ide: bool,
    pub tx_rtr: bool,
    pub tx_id: u32,
    pub tx_dlc: u8,
    pub tx_data: u64,
    pub tx_abort: bool,
    pub cnt_load: bool,
    pub tec_in: u16,
    pub rec_in: u8,
}

impl CoreInputs {
    /// Names of the inputs in [`CoreInputs::words`] order (the model's port order).
    pub const NAMES: [&'static str; 23] = [
        "reset", "rx", "brp", "prop", "ph1", "ph2", "sjw", "triple", "listen_only", "self_test", "single_shot", "host_recovery",
        "recover", "tx_req", "tx_ide", "tx_rtr", "tx_id", "tx_dlc", "tx_data", "tx_abort", "cnt_load", "tec_in", "rec_in",
    ];
    /// The inputs as integers in the model's port order.
    pub fn words(&self) -> [u128; 23] {
        let b = |x: bool| x as u128;
        [
            b(self.reset), b(self.rx), self.brp as u128, self.prop as u128, self.ph1 as u128, self.ph2 as u128, self.sjw as u128,
            b(self.triple), b(self.listen_only), b(self.self_test), b(self.single_shot), b(self.host_recovery), b(self.recover),
            b(self.tx_req), b(self.tx_ide), b(self.tx_rtr), self.tx_id as u128, self.tx_dlc as u128, self.tx_data as u128,
            b(self.tx_abort), b(self.cnt_load), self.tec_in as u128, self.rec_in as u128,
        ]
    }
}

enum Inner {
    Hdl(Box<HdlCore>),
    Model(Box<ModelCore>),
}

/// A controller core on the engine chosen at construction.
pub struct CoreSim {
    /// Inputs for the next [`CoreSim::cycle`].
    pub inp: CoreInputs,
    inner: Inner,
    sync_depth: usize,
    record: Option<Stim>,
}

thread_local! {
    /// Compiled cores loaded from a fresh rust-hdl instance, by synchroniser depth
    /// (loading reads the design's HDL, which costs more than a short simulation).
    static PROTO: RefCell<HashMap<(usize, RecRule), ModelCore>> = RefCell::new(HashMap::new());
}

/// The rust-hdl core as [`CoreSim::with_rule`] powers it up (`drive::init` done).
pub fn fresh_hdl(sync_depth: usize, rec_rule: RecRule) -> HdlCore {
    let mut c = HdlCore::with_sync_depth(sync_depth).with_rec_rule(rec_rule);
    drive::init(&mut c);
    c
}

impl CoreSim {
    /// A core with an RX synchroniser of `sync_depth` flip-flops, powered up
    /// (`drive::init`), on `engine`.
    pub fn new(engine: Engine, sync_depth: usize) -> Self {
        Self::with_rule(engine, sync_depth, RecRule::default())
    }

    /// As [`CoreSim::new`], with the REC rule `rec_rule` for a successful reception (C13).
    pub fn with_rule(engine: Engine, sync_depth: usize, rec_rule: RecRule) -> Self {
        let inner = match engine {
            Engine::RustHdl => Inner::Hdl(Box::new(fresh_hdl(sync_depth, rec_rule))),
            Engine::Compiled => {
                let m = PROTO.with(|p| {
                    let mut p = p.borrow_mut();
                    if let Some(m) = p.get(&(sync_depth, rec_rule)) {
                        return Ok(m.clone());
                    }
                    let m = ModelCore::from_instance(&fresh_hdl(sync_depth, rec_rule))?;
                    p.insert((sync_depth, rec_rule), m.clone());
                    Ok::<_, canstar_rtlc::Error>(m)
                });
                match m {
                    Ok(m) => Inner::Model(Box::new(m)),
                    Err(e) => {
                        fallback_warning("CanCore", &e.to_string());
                        Inner::Hdl(Box::new(fresh_hdl(sync_depth, rec_rule)))
                    }
                }
            }
        };
        CoreSim { inp: CoreInputs { rx: true, ..Default::default() }, inner, sync_depth, record: None }
    }

    /// The engine actually simulating (rust-hdl after a fallback).
    pub fn engine(&self) -> Engine {
        match self.inner {
            Inner::Hdl(_) => Engine::RustHdl,
            Inner::Model(_) => Engine::Compiled,
        }
    }

    /// The rust-hdl block, when that is the engine.
    pub fn hdl(&self) -> Option<&HdlCore> {
        match &self.inner {
            Inner::Hdl(c) => Some(c),
            Inner::Model(_) => None,
        }
    }

    /// RX synchroniser depth.
    pub fn sync_depth(&self) -> usize {
        self.sync_depth
    }

    /// Record the inputs of every clock from now on (a benchmark workload to replay
    /// into any engine, see [`crate::stim`]).
    pub fn start_recording(&mut self) {
        self.record = Some(Stim::new(1, CoreInputs::NAMES.len()));
    }

    /// The recorded inputs (None if recording was never started).
    pub fn take_recording(&mut self) -> Option<Stim> {
        self.record.take()
    }

    /// One clock with [`CoreSim::inp`] (`canstar_hdl::drive::cycle` semantics).
    #[inline]
    pub fn cycle(&mut self) {
        if let Some(r) = self.record.as_mut() {
            r.push(0, &self.inp.words());
            r.next();
        }
        let i = &self.inp;
        match &mut self.inner {
            Inner::Model(m) => {
                m.reset = i.reset;
                m.rx = i.rx;
                m.brp = i.brp & 0x7f;
                m.prop = i.prop & 0xf;
                m.ph1 = i.ph1 & 7;
                m.ph2 = i.ph2 & 7;
                m.sjw = i.sjw & 3;
                m.triple = i.triple;
                m.listen_only = i.listen_only;
                m.self_test = i.self_test;
                m.single_shot = i.single_shot;
                m.host_recovery = i.host_recovery;
                m.recover = i.recover;
                m.tx_req = i.tx_req;
                m.tx_ide = i.tx_ide;
                m.tx_rtr = i.tx_rtr;
                m.tx_id = i.tx_id & 0x1fff_ffff;
                m.tx_dlc = i.tx_dlc & 0xf;
                m.tx_data = i.tx_data;
                m.tx_abort = i.tx_abort;
                m.cnt_load = i.cnt_load;
                m.tec_in = i.tec_in & 0x1ff;
                m.rec_in = i.rec_in;
                m.cycle();
            }
            Inner::Hdl(c) => {
                c.reset.next = i.reset;
                c.rx.next = i.rx;
                c.brp.next = (i.brp as u64).into();
                c.prop.next = (i.prop as u64).into();
                c.ph1.next = (i.ph1 as u64).into();
                c.ph2.next = (i.ph2 as u64).into();
                c.sjw.next = (i.sjw as u64).into();
                c.triple.next = i.triple;
                c.listen_only.next = i.listen_only;
                c.self_test.next = i.self_test;
                c.single_shot.next = i.single_shot;
                c.host_recovery.next = i.host_recovery;
                c.recover.next = i.recover;
                c.tx_req.next = i.tx_req;
                c.tx_ide.next = i.tx_ide;
                c.tx_rtr.next = i.tx_rtr;
                c.tx_id.next = (i.tx_id as u64).into();
                c.tx_dlc.next = (i.tx_dlc as u64).into();
                c.tx_data.next = i.tx_data.into();
                c.tx_abort.next = i.tx_abort;
                c.cnt_load.next = i.cnt_load;
                c.tec_in.next = (i.tec_in as u64).into();
                c.rec_in.next = (i.rec_in as u64).into();
                drive::cycle(c.as_mut());
            }
        }
    }

    /// Trace mode (VCD): the compiled model evaluates every signal on every clock,
    /// so the probe walk shows current values (rust-hdl always does).
    pub fn set_trace(&mut self, on: bool) {
        if let Inner::Model(m) = &mut self.inner {
            m.set_trace(on);
            if on {
                m.settle_all();
            }
        }
    }

    /// Present the signals to `probe` as the rust-hdl block's `accept(name, probe)`.
    pub fn accept(&self, name: &str, probe: &mut dyn Probe) {
        match &self.inner {
            Inner::Hdl(c) => c.accept(name, probe),
            Inner::Model(m) => Model::accept(m.as_ref(), name, probe),
        }
    }
}

macro_rules! view_model {
    (bool: $($b:ident),*; u32: $($n:ident),*) => {
        $(#[inline] fn $b(&self) -> bool { self.$b })*
        $(#[inline] fn $n(&self) -> u32 { self.$n as u32 })*
    };
}

/// The compiled model's output fields.
impl CoreView for ModelCore {
    view_model!(
        bool: tx, tx_done, arb_lost, error, err_tx, rx_valid, rx_ide, rx_rtr, err_warn, cfg_err, dbg_busmon, dbg_sample,
            dbg_tx_rqst, dbg_stuff, dbg_role, dbg_hard_sync, dbg_resync;
        u32: arb_lost_pos, err_kind, err_field, err_pos, rx_id, rx_dlc, tec, rec, state, dbg_field, dbg_pos, dbg_events, dbg_runs
    );
    #[inline]
    fn rx_data(&self) -> u64 {
        self.rx_data
    }
}

macro_rules! view_either {
    ($($f:ident: $t:ty),*) => {
        $(#[inline] fn $f(&self) -> $t {
            match &self.inner {
                Inner::Model(m) => m.$f(),
                Inner::Hdl(c) => c.$f(),
            }
        })*
    };
}

impl CoreView for CoreSim {
    view_either!(
        tx: bool, tx_done: bool, arb_lost: bool, arb_lost_pos: u32, error: bool, err_kind: u32, err_field: u32, err_pos: u32,
        err_tx: bool, rx_valid: bool, rx_ide: bool, rx_rtr: bool, rx_id: u32, rx_dlc: u32, rx_data: u64, tec: u32, rec: u32,
        state: u32, err_warn: bool, cfg_err: bool, dbg_busmon: bool, dbg_sample: bool, dbg_tx_rqst: bool, dbg_field: u32,
        dbg_pos: u32, dbg_stuff: bool, dbg_role: bool, dbg_events: u32, dbg_runs: u32, dbg_hard_sync: bool, dbg_resync: bool
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_words_are_in_port_order() {
        let m = ModelCore::new();
        let names: Vec<&str> = m.info().inputs.iter().map(|p| p.name).collect();
        assert_eq!(names, CoreInputs::NAMES);
    }

    /// Both engines give the same outputs, clock by clock, for a node that idles
    /// then sees a dominant bit train (a check of the input mapping of `cycle`).
    #[test]
    fn engines_agree_on_outputs() {
        let mut cores = [CoreSim::new(Engine::Compiled, 2), CoreSim::new(Engine::RustHdl, 2)];
        assert_eq!(cores[0].engine(), Engine::Compiled);
        assert_eq!(cores[1].engine(), Engine::RustHdl);
        for t in 0..4000u32 {
            for c in cores.iter_mut() {
                c.inp.reset = t < 4;
                c.inp.brp = 0;
                c.inp.prop = 4;
                c.inp.ph1 = 2;
                c.inp.ph2 = 2;
                c.inp.sjw = 1;
                c.inp.rx = !(t > 1500 && (t / 10) % 3 == 0);
                c.inp.tx_req = t > 200;
                c.inp.tx_id = 0x123;
                c.inp.tx_dlc = 2;
                c.inp.tx_data = 0xabcd;
                c.cycle();
            }
            let (a, b) = (&cores[0], &cores[1]);
            let sig = |c: &CoreSim| (c.tx(), c.dbg_field(), c.dbg_pos(), c.dbg_events(), c.tec(), c.rec(), c.error(), c.err_kind());
            assert_eq!(sig(a), sig(b), "clock {t}");
        }
        assert!(cores[0].tec() > 0, "the disturbance made errors");
    }
}
