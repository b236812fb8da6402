//! [`Field`]: the FIELD of the bit in progress (can-protocol.md §4.5), the state of the
//! frame sequencer. Its code (declaration order) is the `field` output of
//! [`super::CanFsm`] and the `err_field` payload; the table is in the
//! [`super`] module documentation.

use rust_hdl::prelude::*;

/// The FIELD of the bit in progress (§4.5). Codes are the declaration order,
/// see the module documentation of [`super`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, LogicState)]
pub enum Field {
    Reset,
    WaitIdle,
    Idle,
    BusOff,
    Sof,
    Ident,
    Srr,
    Ide,
    Rtr,
    ExIdent,
    Resv,
    Dlc,
    Data,
    Crc,
    CrcDel,
    AckSlot,
    AckDel,
    Eof,
    ActFlag,
    PasFlag,
    OvlFlag,
    ErrDel,
    OvlDel,
    Inter,
    Suspend,
}

impl Field {
    /// All fields in code order.
    pub const ALL: [Field; 25] = [
        Field::Reset,
        Field::WaitIdle,
        Field::Idle,
        Field::BusOff,
        Field::Sof,
        Field::Ident,
        Field::Srr,
        Field::Ide,
        Field::Rtr,
        Field::ExIdent,
        Field::Resv,
        Field::Dlc,
        Field::Data,
        Field::Crc,
        Field::CrcDel,
        Field::AckSlot,
        Field::AckDel,
        Field::Eof,
        Field::ActFlag,
        Field::PasFlag,
        Field::OvlFlag,
        Field::ErrDel,
        Field::OvlDel,
        Field::Inter,
        Field::Suspend,
    ];
    /// The field with code `c` (see the module documentation).
    pub fn from_code(c: u64) -> Option<Field> {
        Self::ALL.get(c as usize).copied()
    }
    /// The numeric code of the field.
    pub fn code(self) -> u64 {
        Self::ALL.iter().position(|f| *f == self).unwrap() as u64
    }
    /// The reference model's FIELD name (§4.5).
    pub fn name(self) -> &'static str {
        match self {
            Field::Reset => "Reset",
            Field::WaitIdle => "Wait_For_Bus_Idle",
            Field::Idle => "Bus_Idle",
            Field::BusOff => "Bus_Off",
            Field::Sof => "Start_Of_Frame",
            Field::Ident => "Identifier",
            Field::Srr => "SRR_Bit",
            Field::Ide => "IDE_Bit",
            Field::Rtr => "RTR_Bit",
            Field::ExIdent => "Ex_Identifier",
            Field::Resv => "Reserved_Bits",
            Field::Dlc => "Data_Length_Code",
            Field::Data => "Data_Field",
            Field::Crc => "CRC_Sequence",
            Field::CrcDel => "CRC_Delimiter",
            Field::AckSlot => "ACK_Slot",
            Field::AckDel => "ACK_Delimiter",
            Field::Eof => "End_Of_Frame",
            Field::ActFlag => "Active_Error_Flag",
            Field::PasFlag => "Passive_Error_Flag",
            Field::OvlFlag => "Overload_Flag",
            Field::ErrDel => "Error_Delimiter",
            Field::OvlDel => "Overload_Delimiter",
            Field::Inter => "Intermission",
            Field::Suspend => "Suspend_Transmission",
        }
    }
    /// POSITION `pos` is the one at which the field's decision depends on it
    /// (the sequencer's `at_end`, issue #16; `ext` and `data_bits` from the
    /// receive register).
    pub fn at_end(self, pos: u64, ext: bool, data_bits: u64) -> bool {
        match self {
            Field::WaitIdle | Field::BusOff | Field::Ident => pos == 11,
            Field::ExIdent => pos == 18,
            Field::Resv => ext && pos == 1,
            Field::Dlc => pos == 4,
            Field::Data => pos == data_bits,
            Field::Crc => pos == 15,
            Field::Eof => pos == 7,
            Field::PasFlag => pos == 1,
            Field::ActFlag | Field::OvlFlag => pos == 6,
            Field::ErrDel | Field::OvlDel | Field::Suspend => pos == 8,
            Field::Inter => pos == 3,
            _ => false,
        }
    }
    /// Fields that carry a Tx_/Rx_ role prefix in the trace (§18).
    pub fn has_role(self) -> bool {
        !matches!(self, Field::Reset | Field::WaitIdle | Field::Idle | Field::BusOff)
    }
    /// The field lies in the stuffed area (Start_Of_Frame .. CRC_Sequence).
    pub fn in_stuffed_area(self) -> bool {
        (Field::Sof.code()..=Field::Crc.code()).contains(&self.code())
    }
    /// Hard synchronisation is enabled at every position of the field (§3.3; the
    /// third Intermission bit is the other case).
    pub fn hard_sync(self) -> bool {
        matches!(self, Field::Reset | Field::WaitIdle | Field::Idle | Field::BusOff | Field::Sof | Field::Suspend)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_the_declaration_order_and_the_hardware_encoding() {
        for (i, f) in Field::ALL.iter().enumerate() {
            assert_eq!(f.code(), i as u64);
            assert_eq!(Field::from_code(i as u64), Some(*f));
            // the value a Field signal carries in the RTL (and in Verilog)
            let b: Bits<5> = (*f).into();
            assert_eq!(b.index(), i, "{f:?}");
        }
        assert_eq!(Field::from_code(25), None);
    }

    #[test]
    fn the_stuffed_area_is_sof_to_crc() {
        let area: Vec<Field> = Field::ALL.into_iter().filter(|f| f.in_stuffed_area()).collect();
        assert_eq!(area.first(), Some(&Field::Sof));
        assert_eq!(area.last(), Some(&Field::Crc));
        assert_eq!(area.len(), 10);
    }
}
