//! baudrate program (conformance-tests.md §1), one test per step.
canstar_verify::conformance_tests!("baudrate";
    baudrate_1,
    baudrate_2,
    baudrate_3,
    baudrate_4,
    baudrate_4b,
);
