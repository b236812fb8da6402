//! Single campaign runs, by their printed seeds, that show a hub rule at work in the
//! two-hub system (hub.md §5.17): the same runs `canstar campaign --class C --run-seed S`
//! reproduces.

use canstar_hub::config::HubConfig;
use canstar_recan::campaign::report::RunOutcome;
use canstar_recan::campaign::{self, system, RunPlan, Settings};

/// The run of `class` with `seed`, its hubs configured by `hub` (None: the default).
fn run_with(class: &str, seed: u64, hub: Option<HubConfig>) -> RunOutcome {
    let classes = campaign::select(class).unwrap();
    assert_eq!(classes.len(), 1);
    let s = Settings { seed: 1, reps: 1, hub, ..Settings::default() };
    system::run_plan(&RunPlan { class: classes[0].clone(), rep: 0, seed }, &s)
}

fn run(class: &str, seed: u64) -> RunOutcome {
    run_with(class, seed, None)
}

/// The run of `class` with `seed` with the reference node driver changed by `f`.
fn run_driver(class: &str, seed: u64, f: impl FnOnce(&mut canstar_recan::spec::DriverSpec)) -> RunOutcome {
    let c = campaign::class(class).unwrap();
    let s = Settings { seed: 1, reps: 1, ..Settings::default() };
    let mut b = system::build(&c, seed, &s);
    f(&mut b.spec.network.driver);
    system::run_built(&c, 0, seed, b).outcome
}

/// The default hub configuration with `f` applied.
fn hub(f: impl FnOnce(&mut HubConfig)) -> Option<HubConfig> {
    let mut h = canstar_recan::NetworkSpec::default().hub;
    f(&mut h);
    Some(h)
}

/// The default hub passes `run` (class, seed) with exactly `isolations`, and the hub with
/// `before` applied (the configuration before a change) fails it; returns that failing run.
fn passes_only_by_default(run: (&str, u64), isolations: &[&str], before: impl FnOnce(&mut HubConfig)) -> RunOutcome {
    let (class, seed) = run;
    let o = run_with(class, seed, None);
    assert!(o.pass, "{class} {seed}: {:?}", o.failures);
    assert_eq!(o.isolations, isolations, "{class} {seed}");
    let b = run_with(class, seed, hub(before));
    assert!(!b.pass, "{class} {seed} passes before the change too: {:?}", b.isolations);
    b
}

/// The run failed because the two hubs isolated each other (the star split).
fn partitioned(o: &RunOutcome) -> bool {
    !o.pass && o.failures.iter().any(|f| f.contains("hubs isolated each other"))
}

/// hub.md §5.17: hub 1's output forced dominant about every 1.9 bits. Its dominant bits in
/// the error delimiters count two blames on hub 0's sublinks, which cut hub 1 off before
/// the transmitter behind hub 0 reaches the warning limit (with one blame per delimiter
/// bit it reached 96 and every node lost a controller).
#[test]
fn delimiter_blames_cut_off_a_hub_forcing_dominant_in_time() {
    let o = run("sweep-hub-r2d-e2", 15219089611999315342);
    assert!(o.pass, "{:?}", o.failures);
    assert!(o.worst_healthy < 80, "worst healthy TEC/REC {}", o.worst_healthy);
    assert_eq!(o.isolations.iter().filter(|i| i.starts_with("hub 0 sublink")).count(), 2, "{:?}", o.isolations);
}

/// hub.md §5.17 follower: hub 1's output forced dominant about every 9 bits; the nodes on
/// hub 0 react to its pulses with flags that hub 0 sees in the same delimiter bit as the
/// pulse on its sublinks. Those ports followed the sublinks and count one blame each, so
/// hub 0 cuts off hub 1 and keeps every port (with three blames per port they reached
/// the limit first and hub 0 isolated a healthy port).
#[test]
fn ports_that_follow_the_sublinks_in_a_delimiter_are_spared() {
    let o = run("sweep-hub-r2d-e10", 7512714283061735749);
    assert!(o.pass, "{:?}", o.failures);
    assert!(!o.isolations.iter().any(|i| i.starts_with("hub 0 port")), "{:?}", o.isolations);
    assert_eq!(o.isolations.iter().filter(|i| i.starts_with("hub 0 sublink")).count(), 2, "{:?}", o.isolations);
}

/// hub.md §5.25 sublink follower: hub 1's output flips about every 10 bits, phase-locked
/// with the error frames it causes, so its pulse reaches hub 0's sublinks in error delimiter
/// bit 3 episode after episode. Node 2's controller A on hub 0 flags in reaction, after the
/// sublinks; counted one blame per episode (§5.17), its healthy port reached 48 in the
/// clock the sublinks reached their limit and hub 0 isolated it. As a sublink follower it is
/// blamed, not charged.
#[test]
fn a_port_that_follows_a_sublink_in_a_delimiter_is_not_charged() {
    let o = run("sweep-hub-flip-e10", 17470629488025242632);
    assert!(o.pass, "{:?}", o.failures);
    assert!(!o.isolations.iter().any(|i| i.starts_with("hub 0 port")), "{:?}", o.isolations);
    assert_eq!(o.isolations.iter().filter(|i| i.starts_with("hub 0 sublink")).count(), 2, "{:?}", o.isolations);
}

/// hub.md §5.26: the Receiver's controller B, on hub 1's port 2, has its uplink forced
/// dominant about every 10.75 bits. Some pulses start as hub 1 enters the intermission after
/// an overload delimiter, while hub 0's monitor is a bit ahead: hub 1 takes the pulse for an
/// overload condition, hub 0 for a SOF whose edge came through its sublinks in intermission
/// bit 2, and charged its healthy port 0 and both sublinks as first flaggers for the
/// overload flags that answered it. Its sublinks reached their limit with the faulty port
/// and the hubs isolated each other. Without those charges hub 1 isolates the port alone.
/// A SOF from the peer's node, which reaches this hub a clock or two before its own bit
/// start, must keep its first flaggers: with `early_sof_clocks` 1 a faulty downlink's flags
/// behind hub 1 go uncharged and the hubs isolate each other.
#[test]
fn overload_flags_after_an_early_sof_from_the_peer_are_not_charged() {
    let off = passes_only_by_default(
        ("sweep-up-r2d-e10", 11664831222488605187),
        &["hub 1 port 2@453 (bic 48/48)"],
        |h| h.early_sof_clocks = 0,
    );
    assert!(partitioned(&off), "without the rule: {:?}", off.failures);
    assert!(run("sweep-down-d2r-e10", 14880712450563600277).pass);
    let early = run_with("sweep-down-d2r-e10", 14880712450563600277, hub(|h| h.early_sof_clocks = 1));
    assert!(!early.pass, "early_sof_clocks 1: {:?}", early.isolations);
}

/// hub.md §5.27: a one-bit dominant pulse about every 102 bits on the sublink into hub 1.
/// Where it falls on a recessive bit that the transmitter behind hub 0 follows with
/// dominant bits, only hub 1's monitor finds an error, and the first-flagger rule charges
/// the dominant contenders; a replica charge followed only from a blame registered before
/// the episode started, so the faulty replica went on without one, and hub 0, which charges
/// both of its sublinks for every flag of hub 1, reached its limit first (bit 1503). With
/// the replica charge for the only dominant contender, hub 1 cuts the faulty replica off
/// at its second such episode. The same charge passes a pulse every 2 bits.
#[test]
fn a_first_flagger_against_its_recessive_replica_gets_a_replica_charge() {
    let off = passes_only_by_default(
        ("sweep-sublink-r2d-e100", 7601751665248820364),
        &["hub 1 sublink 0@883 (replica 2/2)"],
        |h| h.ff_replica_charge = false,
    );
    assert!(partitioned(&off), "without the rule: {:?}", off.failures);
    passes_only_by_default(
        ("sweep-sublink-r2d-e2", 14166616403326049450),
        &["hub 0 sublink 0@644 (replica 2/2)"],
        |h| h.ff_replica_charge = false,
    );
}

/// hub.md §5.28: the sublink from hub 0 into hub 1 forced dominant for about 14.5 hub clocks
/// every 2 bits. Hub 1 counts most pulses as glitches and blames nobody for the nodes' flags
/// that follow them, while hub 0 charges both of its sublinks for every flag of hub 1: with
/// the glitch limit 6 hub 1 cut the replica off by the replica rule one bit before hub 0
/// cut off hub 1. With the limit 5 the fifth glitch isolates it ten bits earlier.
#[test]
fn a_sublink_glitching_every_two_bits_is_cut_off_at_its_fifth_glitch() {
    let six = passes_only_by_default(
        ("sweep-sublink-r2d-e2", 16316939522952671778),
        &["hub 1 sublink 1@220 (glitches 5/5)"],
        |h| h.sub_glitch_limit = 6,
    );
    assert!(partitioned(&six), "limit 6: {:?}", six.failures);
}

/// hub.md §5.28: node 1's controller A has its downlink flipping about every 10.6 bits and
/// keeps restarting its error flag. Its hub (hub 0) sees a recessive sliver that the peer's
/// sample missed, so the peer's sublinks carry a dominant run a few tenths of a bit longer
/// than the port's: with the sublink threshold 28 both reached their limit in the same bit
/// and the hubs split; with 29 the port is cut off first and the peer keeps its sublinks.
#[test]
fn the_peer_leaves_a_flagging_port_time_to_reach_its_dominant_run_limit() {
    let t28 = passes_only_by_default(
        ("sweep-down-flip-e10", 18092177680530550086),
        &["hub 0 port 1@604 (dominant run 13/13)"],
        |h| h.sub_dbc_threshold = 28,
    );
    assert_eq!(t28.isolations.iter().filter(|i| i.starts_with("hub 1 sublink")).count(), 2, "threshold 28: {:?}", t28.isolations);
}

/// hub.md §5.19: node 1's controller B loses a dominant bit about every 9 bits on its
/// downlink and flags in what is the last EOF bit for everyone else. The receivers take
/// that bit for an overload condition, the transmitter for a form error (TEC + 8 and a
/// retransmission). With the last-EOF-bit rule hub 1 charges the port for it and isolates
/// it before the transmitter reaches the warning limit; without it node 0's controller B
/// was quarantined at TEC 96 while hub 1's blame counter lagged.
#[test]
fn a_receiver_flagging_in_the_last_eof_bit_is_charged() {
    let class = "sweep-down-d2r-e10";
    let seed = 8225355605758347553;
    let o = run(class, seed);
    assert!(o.pass, "{:?}", o.failures);
    assert!(o.worst_healthy < 96, "worst healthy TEC/REC {}", o.worst_healthy);
    assert!(o.isolations.iter().any(|i| i.starts_with("hub 1 port 1")), "{:?}", o.isolations);
    let off = run_with(class, seed, hub(|h| h.eof_last_rule = false));
    assert!(!off.pass && off.worst_healthy >= 96, "without the rule: {:?}", off.failures);
}

/// hub.md §5.29 (node driver, beyond the published one). Hub 0 faulty; hub 1 cuts it off
/// and the star splits. In `sweep-hub-g6-e2` rep 147 node 0's controller A, on the faulty
/// star, sends frame 0xa0 counter 2 four times without its controller B seeing it, and the
/// published driver then reports it sent: the Receiver, left with its controller B on the
/// healthy star, never gets it. With the copy to the other star node 0's controller B sends
/// it too. In `sweep-hub-r2d-e100` rep 412 a node's tx controller is on the healthy star and its copies
/// go to the faulty one, where one is given up: the frame is reported sent only when the
/// copy is (or is given up), so no later frame overtakes a copy.
#[test]
fn a_frame_sent_only_on_a_faulty_star_is_copied_to_the_other_one() {
    for (class, seed, missed) in [
        ("sweep-hub-g6-e2", 6744485375589422982, "missed 0xa0 counter 2..=2"),
        ("sweep-hub-r2d-e100", 13758353382029262144, "missed 0xa0 counter 22..=22"),
    ] {
        let with = run(class, seed);
        assert!(with.pass, "{class} {seed}: {:?}", with.failures);
        assert!(with.notes.iter().any(|n| n.contains("copied to the other star")), "{class} {seed}: {:?}", with.notes);
        let published = run_driver(class, seed, |d| d.copy_tec = 0);
        assert!(published.failures.iter().any(|f| f.contains(missed)), "{class} {seed} as published: {:?}", published.failures);
        assert!(!published.notes.iter().any(|n| n.contains("copied")), "{:?}", published.notes);
    }
    let given_up = run("sweep-hub-r2d-e100", 13758353382029262144);
    assert!(given_up.notes.iter().any(|n| n.contains("1 given up unsent")), "{:?}", given_up.notes);
}

/// hub.md §5.30 (node driver, beyond the published one). Hub 0 faulty, cut off by hub 1;
/// node 0's controller A, on the faulty star with TEC 0, sends a frame its controller B
/// never sees, and it is reported sent on the omission rule; the Receiver, left on the
/// healthy star, does not get it. When A is quarantined, B sends that frame again before
/// the pending one, unless A reported a transmit error after the CRC of the pending frame.
#[test]
fn the_last_frame_sent_on_the_omission_rule_goes_again_after_a_tx_quarantine() {
    for (seed, missed) in [(16881387309546140847, "missed 0xa0 counter 3..=3"), (9687134118981308336, "missed 0xa0 counter 4..=4")] {
        let class = "sweep-hub-g6-e2";
        let with = run(class, seed);
        assert!(with.pass, "{seed}: {:?}", with.failures);
        assert!(with.notes.iter().any(|n| n.contains("1 unconfirmed frame(s) sent again")), "{seed}: {:?}", with.notes);
        let published = run_driver(class, seed, |d| d.resend_unconfirmed = false);
        assert!(published.failures.iter().any(|f| f.contains(missed)), "{seed} as published: {:?}", published.failures);
    }
    // node 0's tx controller B sends counter 15, the Receiver takes it, and B reports a
    // transmit error in its EOF and is quarantined without reporting it sent: counter 14
    // sent again would reach the Receiver after 15, so it is not
    let late = run("sweep-hub-flip-e100", 7184850286248018629);
    assert!(late.pass, "{:?}", late.failures);
    assert!(!late.notes.iter().any(|n| n.contains("sent again")), "{:?}", late.notes);
}
