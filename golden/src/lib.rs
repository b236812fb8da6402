//! Golden reference model of the CAN 2.0A/B protocol controller (can-protocol.md).
//!
//! This is a plain behavioural model, written directly from the specification and
//! independent of the RTL. It works on the bit level: [`GoldenNode::step`] is called once per
//! sample point with the level the node sampled, processes that bit (destuffing, CRC,
//! arbitration, error detection, fault confinement, §4–§14) and returns what the node drives in
//! the next bit, plus the events of §18 and the FIELD/POSITION label of the processed bit.
//! There is no bit timing here: a bit-timing layer above uses [`GoldenNode::drive`] as the
//! `drive` input of §2.3 and [`GoldenNode::hs_en`] for §3.3.
//!
//! * [`frame`]: [`Frame`], CRC-15 and the bit-level frame builder [`frame::frame_bits`].
//! * [`GoldenBus`]: an ideal bit-level multi-node bus (every node samples the wired-AND of all
//!   drives, through an optional per-node [`RxOverride`]) to run the model without timing.
//! * [`trace`]: the per-bit trace record of §18.
//!
//! Contract of one bit: the node drives [`GoldenNode::drive`] during the bit; the caller
//! computes the bus level, applies the node's receive path and calls `step(sampled)` at the
//! sample point. Counter and state changes caused by the bit are visible right after `step`
//! (§13.4). Host commands ([`GoldenNode::request`], [`GoldenNode::withdraw`],
//! [`GoldenNode::start_recovery`]) take effect at the next `step`.
//!
//! Readings of points the specification leaves open (all consistent with §16/§17):
//!
//! * A CRC error with a dominant ACK_Delimiter is reported once, as `CRC_ERR` (+1).
//! * Exception 1 (§13.3) is decided in passive-flag positions 1..6: the +8 is applied at the
//!   first `D` there; otherwise `EXC1` is reported at position 6.
//! * A flag restarted by a bit error in an *overload* flag is typed like one restarted inside
//!   an active error flag: from the state before the +8 (C14).
//! * A receiver's REC − 1 for a successful reception comes at the ACK slot, once its own
//!   ACK was read back dominant (ISO 11898-1, ISO 16845-1), or with
//!   `Config::rec_bosch_1999` at a recessive End_Of_Frame 7 only (C13). At a receiver's
//!   dominant End_Of_Frame 7 the step reports `RX_OK` (frame delivered) together with
//!   `OVL`, `OLF`.
//! * Membership of a stuff bit in the arbitration field (TEC exception 2) is decided by the
//!   transmitter's own frame format (§7); a test-only recessive r0/r1 read `D` is a bit error.
//! * Listen-only nodes never drive `D` and never change counters; they still follow the
//!   error/overload frame structure so that they stay in step with the bus.
//! * Reset drops a pending request; bus-off keeps it. Outside frames (Bus_Idle, Bus_Off,
//!   integration) the role is `None`. `Bus_Off` POSITION is 1-based inside the current run.

pub mod frame;
mod bus;
mod node;
pub mod trace;

pub use bus::{GoldenBus, RxOverride};
pub use frame::{BitInfo, Frame, FrameVariant};
pub use node::{Config, GoldenNode, StepOut};

/// FIELD names of §4.5 (the reference model's names, used by the trace).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    Reset,
    WaitForBusIdle,
    BusIdle,
    BusOff,
    StartOfFrame,
    Identifier,
    SrrBit,
    IdeBit,
    RtrBit,
    ExIdentifier,
    ReservedBits,
    DataLengthCode,
    DataField,
    CrcSequence,
    CrcDelimiter,
    AckSlot,
    AckDelimiter,
    EndOfFrame,
    ActiveErrorFlag,
    PassiveErrorFlag,
    OverloadFlag,
    ErrorDelimiter,
    OverloadDelimiter,
    Intermission,
    SuspendTransmission,
}

impl Field {
    /// The FIELD name as written in the spec and the trace (without role prefix).
    pub fn name(self) -> &'static str {
        use Field::*;
        match self {
            Reset => "Reset",
            WaitForBusIdle => "Wait_For_Bus_Idle",
            BusIdle => "Bus_Idle",
            BusOff => "Bus_Off",
            StartOfFrame => "Start_Of_Frame",
            Identifier => "Identifier",
            SrrBit => "SRR_Bit",
            IdeBit => "IDE_Bit",
            RtrBit => "RTR_Bit",
            ExIdentifier => "Ex_Identifier",
            ReservedBits => "Reserved_Bits",
            DataLengthCode => "Data_Length_Code",
            DataField => "Data_Field",
            CrcSequence => "CRC_Sequence",
            CrcDelimiter => "CRC_Delimiter",
            AckSlot => "ACK_Slot",
            AckDelimiter => "ACK_Delimiter",
            EndOfFrame => "End_Of_Frame",
            ActiveErrorFlag => "Active_Error_Flag",
            PassiveErrorFlag => "Passive_Error_Flag",
            OverloadFlag => "Overload_Flag",
            ErrorDelimiter => "Error_Delimiter",
            OverloadDelimiter => "Overload_Delimiter",
            Intermission => "Intermission",
            SuspendTransmission => "Suspend_Transmission",
        }
    }
    /// Fields written without a `Tx_`/`Rx_` prefix.
    pub fn is_bare(self) -> bool {
        matches!(self, Field::Reset | Field::WaitForBusIdle | Field::BusIdle | Field::BusOff)
    }
}

/// Frame role (can-protocol.md, Conventions): transmitter, receiver, or none outside frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    None,
    Tx,
    Rx,
}

/// Label of one bit: role, FIELD, POSITION and stuff marker (§4.5, §18).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BitLabel {
    pub role: Role,
    pub field: Field,
    pub pos: u32,
    pub stuff: bool,
}

impl BitLabel {
    /// Trace spelling, e.g. `Tx_Identifier`, `Bus_Idle`.
    pub fn field_name(&self) -> String {
        if self.field.is_bare() {
            self.field.name().to_string()
        } else {
            let p = if self.role == Role::Tx { "Tx_" } else { "Rx_" };
            format!("{p}{}", self.field.name())
        }
    }
}

/// The five error kinds of §9.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    Bit,
    Stuff,
    Crc,
    Form,
    Ack,
}

/// Fault confinement state (§13.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FaultState {
    ErrorActive,
    ErrorPassive,
    BusOff,
}

impl FaultState {
    /// `EA`, `EP` or `BO` (§18).
    pub fn token(self) -> &'static str {
        match self {
            FaultState::ErrorActive => "EA",
            FaultState::ErrorPassive => "EP",
            FaultState::BusOff => "BO",
        }
    }
}

/// Transmit request status (§15, trace record `REQ`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ReqStatus {
    /// No request ever made.
    None,
    Pending,
    Transmitting,
    Done,
    /// Attempt failed with no retry to follow (single-shot, or withdrawn).
    Error,
}

/// Events of one processed bit (§18 tokens).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Event {
    /// A start of frame was sampled (own or foreign).
    Sof,
    /// Arbitration lost at this bit; the value is the bit's POSITION.
    ArbLost(u32),
    /// Error detected at this bit.
    Error(ErrorKind),
    /// An active error flag starts with the next bit.
    Aef,
    /// A passive error flag starts with the next bit.
    Pef,
    /// An overload flag starts with the next bit.
    Olf,
    /// Overload condition.
    Ovl,
    /// k-th consecutive dominant bit after an own flag.
    Daf(u32),
    /// Successful transmission (TEC −1).
    TxOk,
    /// Frame delivered to the host.
    RxOk(Frame),
    /// TEC exception 1 (passive ACK error without dominant bit in the flag) applied.
    Exc1,
    /// TEC exception 2 (stuff error inside arbitration) applied.
    Exc2,
    ToEp,
    ToEa,
    ToBo,
    /// k-th bus-off recovery run of 11 recessive bits completed.
    Run(u32),
    Recovered,
    Warn,
    WarnClr,
}

impl Event {
    /// The §18 token.
    pub fn token(&self) -> String {
        match self {
            Event::Sof => "SOF".into(),
            Event::ArbLost(_) => "ARB_LOST".into(),
            Event::Error(k) => match k {
                ErrorKind::Bit => "BIT_ERR",
                ErrorKind::Stuff => "STUFF_ERR",
                ErrorKind::Crc => "CRC_ERR",
                ErrorKind::Form => "FORM_ERR",
                ErrorKind::Ack => "ACK_ERR",
            }
            .into(),
            Event::Aef => "AEF".into(),
            Event::Pef => "PEF".into(),
            Event::Olf => "OLF".into(),
            Event::Ovl => "OVL".into(),
            Event::Daf(k) => format!("DAF={k}"),
            Event::TxOk => "TX_OK".into(),
            Event::RxOk(_) => "RX_OK".into(),
            Event::Exc1 => "EXC1".into(),
            Event::Exc2 => "EXC2".into(),
            Event::ToEp => "TO_EP".into(),
            Event::ToEa => "TO_EA".into(),
            Event::ToBo => "TO_BO".into(),
            Event::Run(k) => format!("RUN={k}"),
            Event::Recovered => "RECOVERED".into(),
            Event::Warn => "WARN".into(),
            Event::WarnClr => "WARN_CLR".into(),
        }
    }
}
