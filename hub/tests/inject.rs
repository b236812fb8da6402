//! Fault-injection controller (H8).
use canstar_hdl::{drive, flow};
use canstar_hub::frame_state::Field;
use canstar_hub::inject::Injector;
use rand::Rng;

fn step(j: &mut Injector, field: Field, eof_last: bool, button: bool) {
    j.button.next = button;
    j.field.next = field.code().into();
    j.eof_last.next = eof_last;
    j.sample.next = true;
    drive::cycle(j);
    j.sample.next = false;
    drive::cycle(j);
}

#[test]
fn press_arms_field_starts_second_press_stops_at_eof() {
    let mut j = Injector::new(Field::Data.code());
    drive::init(&mut j);
    step(&mut j, Field::Idle, false, false);
    assert!(!j.active.val() && !j.armed.val());
    // press (held for several samples: one edge only)
    step(&mut j, Field::Idle, false, true);
    step(&mut j, Field::Id, false, true);
    step(&mut j, Field::Id, false, true);
    assert!(j.armed.val() && !j.active.val());
    step(&mut j, Field::Dlc, false, false);
    assert!(!j.active.val(), "not in the configured field yet");
    step(&mut j, Field::Data, false, false);
    assert!(j.active.val(), "starts in the data field");
    // the fault stays on across frames until a second press
    step(&mut j, Field::Eof, true, false);
    step(&mut j, Field::Idle, false, false);
    assert!(j.active.val());
    step(&mut j, Field::Id, false, true);
    step(&mut j, Field::Crc, false, false);
    step(&mut j, Field::Eof, false, false);
    assert!(j.active.val(), "still on until the last EOF bit");
    step(&mut j, Field::Eof, true, false);
    assert!(!j.active.val() && !j.armed.val(), "stopped at the end of EOF");
    // a press while armed disarms
    step(&mut j, Field::Idle, false, true);
    step(&mut j, Field::Idle, false, false);
    assert!(j.armed.val());
    step(&mut j, Field::Idle, false, true);
    step(&mut j, Field::Data, false, false);
    assert!(!j.armed.val() && !j.active.val());
}

#[test]
fn reset_clears() {
    let mut j = Injector::new(Field::Idle.code());
    drive::init(&mut j);
    step(&mut j, Field::Idle, false, true);
    step(&mut j, Field::Idle, false, false);
    step(&mut j, Field::Idle, false, false);
    assert!(j.active.val());
    j.reset.next = true;
    drive::cycle(&mut j);
    j.reset.next = false;
    drive::cycle(&mut j);
    assert!(!j.active.val());
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn injector_flow() {
    let mut j = Injector::new(Field::Data.code());
    flow::full_check(&mut j, "injector", 100_000, 9, |j: &mut Injector, rng, c| {
        j.reset.next = c < 2 || rng.gen_ratio(1, 30_000);
        j.sample.next = c % 16 == 12;
        if c % 16 == 0 {
            j.field.next = rng.gen_range(0..16u64).into();
            j.eof_last.next = rng.gen_ratio(1, 10);
        }
        if c % 500 == 0 {
            j.button.next = rng.gen_ratio(1, 3);
        }
    })
    .expect("injector flow");
}
