//! Input stage, port coupler (ANDC), replica coupler (ANDT) and output registers.
//!
//! The input stage is one `canstar_hdl::sync::Synchroniser` (1 or 2 flip-flops, reset
//! and power-up level recessive) per uplink and per incoming sublink.
//!
//! ```text
//!  rx[i] ─► sync(depth) ─► fault(up_fault[i]) ─► u[i] ──► OR dis[i] ──┐
//!                                                                    ├─ AND ─ andc ─► fault(hub_fault[j]) ─► reg ─► hub_tx[j]
//!                                                      efg ──────────┘    │
//!  reh_rx[j] ─► sync(depth) ─► s[j] ──► OR hdis[j] ───────────────────────┴─ AND ─ bt ─► fault(down_fault[i]) ─► reg ─► tx[i]
//! ```
//!
//! Port contract (1 = recessive, 0 = dominant, everywhere):
//! - `rx` (N uplink pins), `reh_rx` (M incoming sublink pins): asynchronous inputs.
//! - `dis[i]` / `hdis[j]`: 1 removes uplink i / sublink j from the coupling (forces it
//!   recessive in the AND). `efg`: the error-flag generator's contribution to ANDC.
//! - `up_fault`, `down_fault`, `hub_fault`: fault-injection code per point, see [`FAULT_NONE`]
//!   and the following constants (all 0 when the hub has no injection hooks).
//! - `u[i]`: the uplink as the coupler and the judges see it (after the input stage and
//!   the uplink fault hook). `s[j]`: synchronised incoming sublink. `andc`, `bt`:
//!   the combinational coupling results (the frame monitor follows `bt`).
//! - `tx[i] = bt` and `hub_tx[j] = andc`, each through one output register. In reset
//!   (`reset` = 1, synchronous, active high) every output register and synchroniser is
//!   forced recessive. The output registers store the inverted level, so they are also
//!   recessive at power-up before the first reset.
//!
//! N and M are generation-time parameters: ports are rust-hdl `Vec`s of signals built by
//! [`Coupler::new`] (they appear in Verilog as `rx$0`, `rx$1`, ...; `$` is legal inside a
//! Verilog identifier). M = 0 is allowed (CANcentrate: then `bt = andc`).
//!
//! Coupling latency (H2): an edge on `rx[i]` reaches `tx[k]` after exactly
//! [`coupling_latency`]`(depth)` = depth + 1 clock edges (depth synchroniser flip-flops,
//! one output register). The same holds from `reh_rx[j]` to `tx[k]` and from `rx[i]` to
//! `hub_tx[j]`.

use canstar_hdl::sync::Synchroniser;
use crate::sigs;
use rust_hdl::prelude::*;

/// Fault-injection code: no fault.
pub const FAULT_NONE: u64 = 0;
/// Fault-injection code: stuck at recessive.
pub const FAULT_STUCK_RECESSIVE: u64 = 1;
/// Fault-injection code: stuck at dominant.
pub const FAULT_STUCK_DOMINANT: u64 = 2;
/// Fault-injection code: bit flip (the signal is inverted, so every bit is flipped once).
pub const FAULT_BIT_FLIP: u64 = 3;

/// Clock edges from an uplink pin change to the downlink pins (H2): the input
/// synchroniser's depth plus one output register.
pub const fn coupling_latency(sync_depth: usize) -> usize {
    sync_depth + 1
}

/// The coupler: input stage, ANDC, ANDT, fault hooks and output registers.
#[derive(LogicBlock)]
pub struct Coupler {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub rx: Vec<Signal<In, Bit>>,
    pub reh_rx: Vec<Signal<In, Bit>>,
    pub dis: Vec<Signal<In, Bit>>,
    pub hdis: Vec<Signal<In, Bit>>,
    pub efg: Signal<In, Bit>,
    pub up_fault: Vec<Signal<In, Bits<2>>>,
    pub down_fault: Vec<Signal<In, Bits<2>>>,
    pub hub_fault: Vec<Signal<In, Bits<2>>>,
    pub tx: Vec<Signal<Out, Bit>>,
    pub hub_tx: Vec<Signal<Out, Bit>>,
    pub u: Vec<Signal<Out, Bit>>,
    pub s: Vec<Signal<Out, Bit>>,
    pub andc: Signal<Out, Bit>,
    pub bt: Signal<Out, Bit>,
    up_sync: Vec<Synchroniser>,
    reh_sync: Vec<Synchroniser>,
    tx_n: Vec<DFF<Bit>>,
    hub_tx_n: Vec<DFF<Bit>>,
    dl: Vec<Signal<Local, Bit>>,
    hl: Vec<Signal<Local, Bit>>,
    ul: Vec<Signal<Local, Bit>>,
    andc_acc: Signal<Local, Bit>,
    bt_acc: Signal<Local, Bit>,
    _n: usize,
    _m: usize,
}

impl Coupler {
    /// A coupler for `n` (>= 1) node ports and `m` (>= 0) sublinks with input
    /// synchronisers of `sync_depth` (1 or 2) flip-flops.
    pub fn new(n: usize, m: usize, sync_depth: usize) -> Self {
        assert!(n >= 1, "a hub needs at least one port");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            rx: sigs(n),
            reh_rx: sigs(m),
            dis: sigs(n),
            hdis: sigs(m),
            efg: Default::default(),
            up_fault: sigs(n),
            down_fault: sigs(n),
            hub_fault: sigs(m),
            tx: sigs(n),
            hub_tx: sigs(m),
            u: sigs(n),
            s: sigs(m),
            andc: Default::default(),
            bt: Default::default(),
            up_sync: (0..n).map(|_| Synchroniser::new(sync_depth)).collect(),
            reh_sync: (0..m).map(|_| Synchroniser::new(sync_depth)).collect(),
            tx_n: (0..n).map(|_| Default::default()).collect(),
            hub_tx_n: (0..m).map(|_| Default::default()).collect(),
            dl: sigs(n),
            hl: sigs(m),
            ul: sigs(n),
            andc_acc: Default::default(),
            bt_acc: Default::default(),
            _n: n,
            _m: m,
        }
    }
    pub fn ports(&self) -> usize {
        self._n
    }
    pub fn sublinks(&self) -> usize {
        self._m
    }
}

impl Logic for Coupler {
    #[hdl_gen]
    fn update(&mut self) {
        // Outputs are assigned exactly once per evaluation (see the hub module docs).
        self.andc_acc.next = self.efg.val();
        for i in 0..self._n {
            self.up_sync[i].clock.next = self.clock.val();
            self.up_sync[i].reset.next = self.reset.val();
            self.up_sync[i].d.next = self.rx[i].val();
            if self.up_fault[i].val() == 1 {
                self.ul[i].next = true;
            } else if self.up_fault[i].val() == 2 {
                self.ul[i].next = false;
            } else if self.up_fault[i].val() == 3 {
                self.ul[i].next = !self.up_sync[i].q.val();
            } else {
                self.ul[i].next = self.up_sync[i].q.val();
            }
            self.u[i].next = self.ul[i].val();
            self.andc_acc.next = self.andc_acc.val() & (self.ul[i].val() | self.dis[i].val());
        }
        self.andc.next = self.andc_acc.val();
        self.bt_acc.next = self.andc_acc.val();
        for j in 0..self._m {
            self.reh_sync[j].clock.next = self.clock.val();
            self.reh_sync[j].reset.next = self.reset.val();
            self.reh_sync[j].d.next = self.reh_rx[j].val();
            self.s[j].next = self.reh_sync[j].q.val();
            self.bt_acc.next = self.bt_acc.val() & (self.reh_sync[j].q.val() | self.hdis[j].val());
            if self.hub_fault[j].val() == 1 {
                self.hl[j].next = true;
            } else if self.hub_fault[j].val() == 2 {
                self.hl[j].next = false;
            } else if self.hub_fault[j].val() == 3 {
                self.hl[j].next = !self.andc_acc.val();
            } else {
                self.hl[j].next = self.andc_acc.val();
            }
            self.hub_tx_n[j].clock.next = self.clock.val();
            self.hub_tx_n[j].d.next = !self.hl[j].val();
            if self.reset.val() {
                self.hub_tx_n[j].d.next = false;
            }
            self.hub_tx[j].next = !self.hub_tx_n[j].q.val();
        }
        self.bt.next = self.bt_acc.val();
        for i in 0..self._n {
            if self.down_fault[i].val() == 1 {
                self.dl[i].next = true;
            } else if self.down_fault[i].val() == 2 {
                self.dl[i].next = false;
            } else if self.down_fault[i].val() == 3 {
                self.dl[i].next = !self.bt_acc.val();
            } else {
                self.dl[i].next = self.bt_acc.val();
            }
            self.tx_n[i].clock.next = self.clock.val();
            self.tx_n[i].d.next = !self.dl[i].val();
            if self.reset.val() {
                self.tx_n[i].d.next = false;
            }
            self.tx[i].next = !self.tx_n[i].q.val();
        }
    }
}

canstar_hdl::impl_clocked!(Coupler);
