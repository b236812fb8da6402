//! idle program (conformance-tests.md §9), one test per step.
canstar_verify::conformance_tests!("idle";
    idle_1,
    idle_2,
    idle_3,
    idle_4,
    idle_5,
    idle_6,
    idle_7,
    idle_8,
    idle_9,
    idle_10,
    idle_11,
    idle_12,
    idle_13,
);
