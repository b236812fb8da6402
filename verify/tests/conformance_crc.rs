//! crc program (conformance-tests.md §4), one test per step.
canstar_verify::conformance_tests!("crc";
    crc_rx_1,
    crc_rx_2,
    crc_tx_1,
    crc_tx_2,
    crc_tx_3,
    crc_tx_4,
    crc_tx_5,
    crc_tx_6,
    crc_tx_7,
    crc_tx_8,
);
