//! extd_id (§7 of the plan): IDE recognition and arbitration around IDE.
//! Frames with a recessive r0 or a dominant SRR come from the scripted
//! transmitter (a third bus participant); the RTL N2 then only receives.
use super::*;

/// The frame condition columns of §7 of the plan: (level of the stuff bit right before
/// IDE, level of the bit right after IDE, is that bit a stuff bit).
fn around_ide(f: &Frame, o: BuildOptions) -> (Option<bool>, bool, bool) {
    let bits = bus_bits(f, o, false);
    let k = bits.iter().position(|b| b.field == Field::Ide).unwrap();
    let before = if bits[k - 1].stuff { Some(bits[k - 1].level) } else { None };
    (before, bits[k + 1].level, bits[k + 1].stuff)
}

/// ID 17 in the 29-bit numbering (ID28..ID0): the first extension bit.
fn id17(f: &Frame) -> bool {
    (f.id >> 17) & 1 == 1
}

#[allow(clippy::type_complexity)]
struct RxStep {
    name: &'static str,
    frame: Frame,
    opts: BuildOptions,
    cond: Box<dyn Fn(&Frame, BuildOptions) -> bool>,
}

#[allow(clippy::type_complexity)]
fn rx_steps() -> Vec<RxStep> {
    let dflt = BuildOptions::default();
    let r0r = BuildOptions { r0: true, ..dflt };
    let srr_d = BuildOptions { srr: false, ..dflt };
    let s = |name, frame, opts, cond: Box<dyn Fn(&Frame, BuildOptions) -> bool>| RxStep { name, frame, opts, cond };
    vec![
        s("extd_id_rx_1", Frame::remote(false, 0x28F, 0), dflt, Box::new(|f, o| matches!(around_ide(f, o), (Some(false), false, _)))),
        s("extd_id_rx_2", Frame::remote(false, 0x28F, 0), r0r, Box::new(|f, o| matches!(around_ide(f, o), (Some(false), true, _)))),
        s("extd_id_rx_3", Frame::std(0x290, &[]), dflt, Box::new(|f, o| matches!(around_ide(f, o), (Some(true), false, _)))),
        s("extd_id_rx_4", Frame::std(0x290, &[]), r0r, Box::new(|f, o| matches!(around_ide(f, o), (Some(true), true, _)))),
        s("extd_id_rx_5", Frame::std(0x288, &[]), dflt, Box::new(|f, o| matches!(around_ide(f, o), (_, true, true)))),
        s("extd_id_rx_6", Frame::ext(0x0A0CA5A5, &[]), dflt, Box::new(|f, o| matches!(around_ide(f, o), (_, false, true)))),
        s("extd_id_rx_7", Frame::ext(0x0A3CA5A5, &[]), dflt, Box::new(|f, o| matches!(around_ide(f, o), (Some(false), _, _)) && !id17(f))),
        s("extd_id_rx_8", Frame::ext(0x0A3EA5A5, &[]), dflt, Box::new(|f, o| matches!(around_ide(f, o), (Some(false), _, _)) && id17(f))),
        s("extd_id_rx_9", Frame::ext(0x0A40A5A5, &[]), srr_d, Box::new(|f, o| matches!(around_ide(f, o), (Some(true), _, _)) && !id17(f))),
        s("extd_id_rx_10", Frame::ext(0x0A42A5A5, &[]), srr_d, Box::new(|f, o| matches!(around_ide(f, o), (Some(true), _, _)) && id17(f))),
    ]
}

fn quiet(b: &Bench, marks: &[usize]) -> Result<(), String> {
    for (i, &m) in marks.iter().enumerate() {
        let flags = b.since(i, m).iter().filter(|r| r.ev & ((1 << EV_AEF) | (1 << EV_PEF) | (1 << EV_OLF)) != 0).count();
        ensure!(flags == 0, "N{} flagged:{}", i + 1, b.dump_events(i, m));
        ensure!((b.tec(i), b.rec(i)) == (0, 0), "N{} TEC {} REC {}", i + 1, b.tec(i), b.rec(i));
    }
    Ok(())
}

fn rx_one(b: &mut Bench, s: &RxStep) -> Result<(), String> {
    ensure!((s.cond)(&s.frame, s.opts), "frame {:?} does not meet the step's condition at IDE", s.frame);
    let marks = [b.mark(0), b.mark(1)];
    let rx0 = b.node(0).received().len();
    if s.opts == BuildOptions::default() {
        b.node_mut(1).request(s.frame.clone());
    } else {
        let h = b.script.unwrap();
        b.sim.get_mut(h).send(script_bits(&s.frame, s.opts));
    }
    b.run_bits(5);
    b.run_idle(300)?;
    check_delivered(b, 0, rx0, std::slice::from_ref(&s.frame))?;
    quiet(b, &marks)
}

struct ArbStep {
    name: &'static str,
    n1: Frame,
    n2: Frame,
    /// N2's frame comes from the scripted transmitter with these options.
    n2_opts: Option<BuildOptions>,
    lost_at: (Field, u32),
}

/// Position (1-based Ex_Identifier) of the first bit where two 18-bit extensions differ.
fn first_diff(a: u32, b: u32) -> u32 {
    18 - (31 - (a ^ b).leading_zeros())
}

fn arb_steps() -> Vec<ArbStep> {
    let x = 0x2A5u32;
    let ext = |e: u32| (x << 18) | e;
    let srr_d = Some(BuildOptions { srr: false, ..BuildOptions::default() });
    let a = |name, n1, n2, n2_opts, lost_at| ArbStep { name, n1, n2, n2_opts, lost_at };
    vec![
        a("extd_id_arb_1", Frame::remote(false, x, 1), Frame::std(x, &[0x11]), None, (Field::Rtr, 1)),
        a("extd_id_arb_2", Frame::remote(false, x, 1), Frame::ext(ext(0x155), &[0x22]), srr_d, (Field::Rtr, 1)),
        a("extd_id_arb_3", Frame::ext(ext(0x3C3), &[0x33]), Frame::std(x, &[0x44]), None, (Field::Srr, 1)),
        a("extd_id_arb_4", Frame::ext(ext(0x3C3), &[0x55]), Frame::remote(false, x, 2), None, (Field::Ide, 1)),
        a("extd_id_arb_5", Frame::ext(ext(0x2F0F0), &[0x66]), Frame::ext(ext(0x2E0F0), &[0x77]), None, (Field::ExIdent, first_diff(0x2F0F0, 0x2E0F0))),
        a("extd_id_arb_6", Frame::remote(true, ext(0x1234), 3), Frame::ext(ext(0x1234), &[0x88]), None, (Field::Rtr, 1)),
        a("extd_id_arb_7", Frame::ext(ext(0x0F0F), &[0x99]), Frame::ext(ext(0x0F0F), &[0xAA]), srr_d, (Field::Srr, 1)),
    ]
}

fn arb_one(b: &mut Bench, s: &ArbStep) -> Result<(), String> {
    let marks = [b.mark(0), b.mark(1)];
    let (rx1, rx2, tx1) = (b.node(0).received().len(), b.node(1).received().len(), b.node(0).sent().len());
    b.node_mut(0).request(s.n1.clone());
    match s.n2_opts {
        None => b.node_mut(1).request(s.n2.clone()),
        Some(o) => {
            let h = b.script.unwrap();
            b.sim.get_mut(h).send_with(script_bits(&s.n2, o));
        }
    }
    b.run_until(600, |b| b.node(0).sent().len() > tx1).map_err(|e| format!("N1 did not send: {e}{}", b.dump_events(0, marks[0])))?;
    b.run_idle(100)?;
    let lost = b.events(0, marks[0], EV_ARB_LOST);
    ensure!(lost.len() == 1, "expected one ARB_LOST at N1:{}", b.dump_events(0, marks[0]));
    let l = lost[0];
    ensure!((l.field, l.pos) == s.lost_at && l.tx_role, "ARB_LOST at {l}, expected {}{}", s.lost_at.0.name(), s.lost_at.1);
    // N1 drives recessive from the next bit until its ACK slot.
    let k = b.since(0, marks[0]).iter().position(|r| r.has(EV_ARB_LOST)).unwrap();
    for r in b.since(0, marks[0])[k + 1..].iter().take_while(|r| r.field != Field::AckSlot) {
        ensure!(r.drove && !r.tx_role, "N1 after losing: {r}");
    }
    check_delivered(b, 0, rx1, std::slice::from_ref(&s.n2))?;
    let want2: Vec<Frame> = if s.n2_opts.is_some() { vec![s.n2.clone(), s.n1.clone()] } else { vec![s.n1.clone()] };
    check_delivered(b, 1, rx2, &want2)?;
    quiet(b, &marks)
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], true);
    for s in rx_steps() {
        let r = rx_one(&mut b, &s);
        ctx.record(s.name, r);
    }
    let tx = [
        ("extd_id_tx_1", Frame::remote(false, 0x28F, 0)),
        ("extd_id_tx_2", Frame::std(0x290, &[])),
        ("extd_id_tx_3", Frame::std(0x288, &[])),
        ("extd_id_tx_4", Frame::ext(0x0A0CA5A5, &[])),
        ("extd_id_tx_5", Frame::ext(0x0A3CA5A5, &[])),
        ("extd_id_tx_6", Frame::ext(0x0A3EA5A5, &[])),
    ];
    for (name, f) in tx {
        let marks = [b.mark(0), b.mark(1)];
        let r = super::dlc::exchange(&mut b, 0, 1, &f).and_then(|_| quiet(&b, &marks));
        ctx.record(name, r);
    }
    for s in arb_steps() {
        let r = arb_one(&mut b, &s);
        ctx.record(s.name, r);
    }
}
