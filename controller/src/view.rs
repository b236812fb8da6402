//! [`CoreView`]: reading the outputs and the debug bundle of a [`CanCore`] the same
//! way from any simulation engine (the rust-hdl block here, the compiled model in
//! `canstar-models`), so host models and tracers do not branch on the engine.

use crate::core::CanCore;

/// The outputs of a CAN controller core after a clock (names of [`CanCore`]'s
/// ports; multi-bit values as integers).
pub trait CoreView {
    fn tx(&self) -> bool;
    fn tx_done(&self) -> bool;
    fn arb_lost(&self) -> bool;
    fn arb_lost_pos(&self) -> u32;
    fn error(&self) -> bool;
    fn err_kind(&self) -> u32;
    fn err_field(&self) -> u32;
    fn err_pos(&self) -> u32;
    fn err_tx(&self) -> bool;
    fn rx_valid(&self) -> bool;
    fn rx_ide(&self) -> bool;
    fn rx_rtr(&self) -> bool;
    fn rx_id(&self) -> u32;
    fn rx_dlc(&self) -> u32;
    fn rx_data(&self) -> u64;
    fn tec(&self) -> u32;
    fn rec(&self) -> u32;
    fn state(&self) -> u32;
    fn err_warn(&self) -> bool;
    fn cfg_err(&self) -> bool;
    fn dbg_busmon(&self) -> bool;
    fn dbg_sample(&self) -> bool;
    fn dbg_tx_rqst(&self) -> bool;
    fn dbg_field(&self) -> u32;
    fn dbg_pos(&self) -> u32;
    fn dbg_stuff(&self) -> bool;
    fn dbg_role(&self) -> bool;
    fn dbg_events(&self) -> u32;
    fn dbg_runs(&self) -> u32;
    fn dbg_hard_sync(&self) -> bool;
    fn dbg_resync(&self) -> bool;

    /// The received frame on the `rx_*` outputs (valid on the clock `rx_valid` is high).
    fn rx_frame(&self) -> crate::frame::Frame {
        crate::frame::Frame::from_native(self.rx_ide(), self.rx_rtr(), self.rx_id(), self.rx_dlc() as u8, self.rx_data())
    }
    /// Transmit error counter (256 and above: bus-off).
    fn tec_value(&self) -> u32 {
        self.tec()
    }
    /// Receive error counter.
    fn rec_value(&self) -> u32 {
        self.rec()
    }
    /// 0 error-active, 1 error-passive, 2 bus-off.
    fn state_value(&self) -> u32 {
        self.state()
    }
    /// FIELD of the bit in progress (between sample points: of the next bit).
    fn field(&self) -> crate::fsm::Field {
        crate::fsm::Field::from_code(self.dbg_field() as u64).unwrap_or(crate::fsm::Field::Reset)
    }
    /// POSITION of the bit in progress.
    fn pos(&self) -> u32 {
        self.dbg_pos()
    }
}

macro_rules! view_hdl {
    (bool: $($b:ident),*; u32: $($n:ident),*) => {
        $(fn $b(&self) -> bool { self.$b.val() })*
        $(fn $n(&self) -> u32 { self.$n.val().index() as u32 })*
    };
}

/// The rust-hdl block, read with `.val()` between clocks.
impl CoreView for CanCore {
    view_hdl!(
        bool: tx, tx_done, arb_lost, error, err_tx, rx_valid, rx_ide, rx_rtr, err_warn, cfg_err, dbg_busmon, dbg_sample,
            dbg_tx_rqst, dbg_stuff, dbg_role, dbg_hard_sync, dbg_resync;
        u32: arb_lost_pos, err_kind, err_field, err_pos, rx_id, rx_dlc, tec, rec, state, dbg_field, dbg_pos, dbg_events, dbg_runs
    );
    fn rx_data(&self) -> u64 {
        self.rx_data.val().to_u64()
    }
}
