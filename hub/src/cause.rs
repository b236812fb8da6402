//! Why a judge unit isolated its input: the counters of [`crate::judge::JudgeUnit`]
//! read in the clock before its `dis` output rose, against the unit's limits. This is
//! the isolation condition of `JudgeUnit::update` ("isolation"), restated for the
//! simulation's reports (`canstar campaign --events`); the hub itself has no such output.

use crate::judge::JudgeParams;

/// The counters of one judge unit at one clock (`pgc` and `rep_cnt` are 0 in port units).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JudgeCounts {
    pub bic: u64,
    pub life: u64,
    pub dbc: u64,
    pub gc: u64,
    pub pgc: u64,
    pub rep_cnt: u64,
    /// The unit was charged while the hub's peer guard (hub.md §5.20) was on (ports only).
    pub guard: bool,
}

/// Every isolation rule the counts meet, e.g. `"bic 80/80"` or
/// `"dominant run 28/28, lifetime 32/32"`; `"no counter at its limit"` if none does
/// (the unit was isolated by something this reading does not cover).
pub fn isolation_cause(p: &JudgeParams, sublink: bool, c: &JudgeCounts) -> String {
    let mut v: Vec<String> = vec![];
    let mut rule = |name: &str, value: u64, limit: u64| {
        if value >= limit {
            v.push(format!("{name} {value}/{limit}"));
        }
    };
    rule("bic", c.bic, p.bic_limit);
    rule("lifetime", c.life, p.life_limit);
    rule("dominant run", c.dbc, p.dbc_threshold);
    rule("glitches", c.gc, p.glitch_limit);
    if sublink {
        rule("peer-hub glitches", c.pgc, p.peer_glitch_limit);
        rule("replica", c.rep_cnt, p.replica_limit);
    }
    if c.guard && !sublink {
        v.push("peer guard".into());
    }
    if v.is_empty() {
        "no counter at its limit".into()
    } else {
        v.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::HubConfig;

    #[test]
    fn names_every_rule_at_its_limit() {
        let cfg = HubConfig::default();
        let (pp, sp) = (cfg.port_params(), cfg.sublink_params());
        let none = JudgeCounts::default();
        assert_eq!(isolation_cause(&pp, false, &none), "no counter at its limit");
        let bic = JudgeCounts { bic: pp.bic_limit, ..none };
        assert_eq!(isolation_cause(&pp, false, &bic), format!("bic {0}/{0}", pp.bic_limit));
        let below = JudgeCounts { bic: pp.bic_limit - 1, life: pp.life_limit - 1, dbc: pp.dbc_threshold - 1, gc: pp.glitch_limit - 1, ..none };
        assert_eq!(isolation_cause(&pp, false, &below), "no counter at its limit");
        let two = JudgeCounts { dbc: pp.dbc_threshold, life: pp.life_limit + 1, ..none };
        assert_eq!(
            isolation_cause(&pp, false, &two),
            format!("lifetime {}/{}, dominant run {2}/{2}", pp.life_limit + 1, pp.life_limit, pp.dbc_threshold)
        );
        // the peer-hub and replica rules are sublink rules only
        let peer = JudgeCounts { pgc: sp.peer_glitch_limit, rep_cnt: sp.replica_limit, ..none };
        assert_eq!(isolation_cause(&pp, false, &peer), "no counter at its limit");
        assert_eq!(
            isolation_cause(&sp, true, &peer),
            format!("peer-hub glitches {0}/{0}, replica {1}/{1}", sp.peer_glitch_limit, sp.replica_limit)
        );
        // the peer guard isolates a charged port whatever its counters (hub.md §5.20)
        let guard = JudgeCounts { bic: 16, guard: true, ..none };
        assert_eq!(isolation_cause(&pp, false, &guard), "peer guard");
        assert_eq!(isolation_cause(&sp, true, &guard), "no counter at its limit");
        let g = JudgeCounts { gc: sp.glitch_limit, ..none };
        assert_eq!(isolation_cause(&sp, true, &g), format!("glitches {0}/{0}", sp.glitch_limit));
    }
}
