//! The complete hub: [`Hub`] = [`HubCore`] plus its frame monitor (the port table is
//! in [`crate::hub`]; configuration: [`crate::config::HubConfig`]).
//!
//! The frame monitor is `canstar_controller::CanCore` in listen-only mode, fed with the
//! coupled bit `bt` and the hub's bit timing, and the [`MonitorAdapter`] maps its debug
//! bundle onto the `mon_*` inputs of [`HubCore`].

use crate::config::HubConfig;
use crate::frame_state::MonitorAdapter;
use crate::hub::HubCore;
use canstar_controller::CanCore;
use crate::sigs;
use rust_hdl::prelude::*;

/// The complete hub: [`HubCore`] plus its frame monitor, the CAN controller
/// (`canstar_controller::CanCore`, listen-only, following BT with the hub's bit timing)
/// and the [`MonitorAdapter`] that maps the controller's debug bundle onto the frame
/// state C. Ports: those of [`HubCore`] without the `mon_*` inputs and without `bt`.
#[derive(LogicBlock)]
pub struct Hub {
    pub clock: Signal<In, Clock>,
    pub rst_n: Signal<In, Bit>,
    pub inject_fault: Signal<In, Bit>,
    pub rx: Vec<Signal<In, Bit>>,
    pub reh_rx: Vec<Signal<In, Bit>>,
    pub tx: Vec<Signal<Out, Bit>>,
    pub hub_tx: Vec<Signal<Out, Bit>>,
    pub isolated: Vec<Signal<Out, Bit>>,
    pub silent: Vec<Signal<Out, Bit>>,
    pub sub_isolated: Vec<Signal<Out, Bit>>,
    pub frame_state: Signal<Out, Bits<4>>,
    pub efg_active: Signal<Out, Bit>,
    pub inject_active: Signal<Out, Bit>,
    pub bic: Vec<Signal<Out, Bits<8>>>,
    pub dbc: Vec<Signal<Out, Bits<5>>>,
    pub nack: Vec<Signal<Out, Bits<3>>>,
    pub sub_bic: Vec<Signal<Out, Bits<8>>>,
    pub sub_dbc: Vec<Signal<Out, Bits<5>>>,
    pub sub_rep: Vec<Signal<Out, Bits<3>>>,
    core: HubCore,
    monitor: CanCore,
    adapter: MonitorAdapter,
    brp: Constant<Bits<5>>,
    prop: Constant<Bits<3>>,
    ph1: Constant<Bits<3>>,
    ph2: Constant<Bits<3>>,
    sjw: Constant<Bits<2>>,
    _n: usize,
    _m: usize,
    _dn: usize,
    _dm: usize,
}

/// Synchroniser depth of the monitor's RX input: BT is already synchronous.
pub const MONITOR_SYNC_DEPTH: usize = 1;

impl Hub {
    /// Build a hub with its frame monitor. Panics if the configuration is invalid.
    pub fn new(cfg: &HubConfig) -> Self {
        let core = HubCore::new(cfg);
        let (n, m) = (cfg.ports, cfg.sublinks);
        let (dn, dm) = if cfg.debug { (n, m) } else { (0, 0) };
        let t = cfg.timing;
        let bs_delay = (t.ph2 * t.brp).saturating_sub(2) as u64;
        let (brp, prop, ph1, ph2, sjw) = t.fields();
        Self {
            clock: Default::default(),
            rst_n: Default::default(),
            inject_fault: Default::default(),
            rx: sigs(n),
            reh_rx: sigs(m),
            tx: sigs(n),
            hub_tx: sigs(m),
            isolated: sigs(n),
            silent: sigs(n),
            sub_isolated: sigs(m),
            frame_state: Default::default(),
            efg_active: Default::default(),
            inject_active: Default::default(),
            bic: sigs(dn),
            dbc: sigs(dn),
            nack: sigs(dn),
            sub_bic: sigs(dm),
            sub_dbc: sigs(dm),
            sub_rep: sigs(dm),
            core,
            monitor: CanCore::with_sync_depth(MONITOR_SYNC_DEPTH),
            adapter: MonitorAdapter::new(bs_delay),
            brp: Constant::new((brp as u64).into()),
            prop: Constant::new((prop as u64).into()),
            ph1: Constant::new((ph1 as u64).into()),
            ph2: Constant::new((ph2 as u64).into()),
            sjw: Constant::new((sjw as u64).into()),
            _n: n,
            _m: m,
            _dn: dn,
            _dm: dm,
        }
    }
    /// The hub without its monitor (simulation probes: `blame_any`, judge units, `bt`).
    pub fn core(&self) -> &HubCore {
        &self.core
    }
    /// The frame monitor (simulation probe).
    pub fn monitor(&self) -> &CanCore {
        &self.monitor
    }
}

impl Logic for Hub {
    #[hdl_gen]
    fn update(&mut self) {
        // frame monitor: the CAN controller, listen-only, on BT
        self.monitor.clock.next = self.clock.val();
        self.monitor.reset.next = self.core.reset_out.val();
        self.monitor.rx.next = self.core.bt.val();
        self.monitor.brp.next = bit_cast::<7, 5>(self.brp.val());
        self.monitor.prop.next = bit_cast::<4, 3>(self.prop.val());
        self.monitor.ph1.next = self.ph1.val();
        self.monitor.ph2.next = self.ph2.val();
        self.monitor.sjw.next = self.sjw.val();
        self.monitor.triple.next = false;
        self.monitor.listen_only.next = true;
        self.monitor.self_test.next = false;
        self.monitor.single_shot.next = false;
        self.monitor.host_recovery.next = false;
        self.monitor.recover.next = false;
        self.monitor.tx_req.next = false;
        self.monitor.tx_ide.next = false;
        self.monitor.tx_rtr.next = false;
        self.monitor.tx_id.next = 0.into();
        self.monitor.tx_dlc.next = 0.into();
        self.monitor.tx_data.next = 0.into();
        self.monitor.tx_abort.next = false;
        self.monitor.cnt_load.next = false;
        self.monitor.tec_in.next = 0.into();
        self.monitor.rec_in.next = 0.into();
        // frame state adapter
        self.adapter.clock.next = self.clock.val();
        self.adapter.reset.next = self.core.reset_out.val();
        self.adapter.sample.next = self.monitor.dbg_sample.val();
        self.adapter.field.next = self.monitor.dbg_field.val();
        self.adapter.pos.next = self.monitor.dbg_pos.val();
        self.adapter.events.next = self.monitor.dbg_events.val();
        self.adapter.stuff.next = self.monitor.dbg_stuff.val();
        // hub core
        self.core.clock.next = self.clock.val();
        self.core.rst_n.next = self.rst_n.val();
        self.core.inject_fault.next = self.inject_fault.val();
        self.core.mon_sample.next = self.adapter.mon_sample.val();
        self.core.mon_bit_start.next = self.adapter.bit_start.val();
        self.core.mon_field.next = self.adapter.mon_field.val();
        self.core.mon_pos.next = self.adapter.mon_pos.val();
        self.core.mon_crc_ok.next = self.adapter.mon_crc_ok.val();
        self.core.mon_frame_ok.next = self.adapter.mon_frame_ok.val();
        self.core.mon_error.next = self.adapter.mon_error.val();
        self.core.mon_stuff.next = self.adapter.mon_stuff.val();
        self.frame_state.next = self.core.frame_state.val();
        self.efg_active.next = self.core.efg_active.val();
        self.inject_active.next = self.core.inject_active.val();
        for i in 0..self._n {
            self.core.rx[i].next = self.rx[i].val();
            self.tx[i].next = self.core.tx[i].val();
            self.isolated[i].next = self.core.isolated[i].val();
            self.silent[i].next = self.core.silent[i].val();
        }
        for j in 0..self._m {
            self.core.reh_rx[j].next = self.reh_rx[j].val();
            self.hub_tx[j].next = self.core.hub_tx[j].val();
            self.sub_isolated[j].next = self.core.sub_isolated[j].val();
        }
        for i in 0..self._dn {
            self.bic[i].next = self.core.bic[i].val();
            self.dbc[i].next = self.core.dbc[i].val();
            self.nack[i].next = self.core.nack[i].val();
        }
        for j in 0..self._dm {
            self.sub_bic[j].next = self.core.sub_bic[j].val();
            self.sub_dbc[j].next = self.core.sub_dbc[j].val();
            self.sub_rep[j].next = self.core.sub_rep[j].val();
        }
    }
}

canstar_hdl::impl_clocked!(Hub);
