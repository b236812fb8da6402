//! overload program (conformance-tests.md), one test per step.
canstar_verify::conformance_tests!("overload";
    overload_rx_1a,
    overload_rx_1b,
    overload_rx_1c,
    overload_rx_1d,
    overload_rx_2,
    overload_rx_3,
    overload_tx_1a,
    overload_tx_1b,
    overload_tx_1c,
    overload_tx_2,
    overload_tx_3,
    overload_tx_4,
);
