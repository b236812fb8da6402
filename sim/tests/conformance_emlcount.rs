//! emlcount program (conformance-tests.md §6), tx_7..tx_15 only; one test per step.
canstar_sim::conformance_tests!("emlcount";
    emlcount_tx_7,
    emlcount_tx_8,
    emlcount_tx_9,
    emlcount_tx_10,
    emlcount_tx_11,
    emlcount_tx_12,
    emlcount_tx_13,
    emlcount_tx_14,
    emlcount_tx_15,
);
