//! A campaign as a JUnit XML report, for CI systems that show per-class results:
//! one test suite per campaign, one test case per class, a failure per class that
//! had failing runs (with the command that reruns each one).

use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};

use super::report::CampaignReport;

/// The JUnit XML of `report`.
pub fn xml(report: &CampaignReport) -> String {
    let mut suite = TestSuite::new("canstar-campaign");
    for s in report.summaries() {
        let status = if s.passes == s.runs {
            TestCaseStatus::success()
        } else {
            let failing: Vec<String> = report
                .runs
                .iter()
                .filter(|r| r.class == s.class && !r.pass)
                .map(|r| format!("rep {} (canstar campaign --class {} --run-seed {}): {}", r.rep, r.class, r.seed, r.failures.join("; ")))
                .collect();
            let mut st = TestCaseStatus::non_success(NonSuccessKind::Failure);
            st.set_message(format!("{} of {} runs failed", s.runs - s.passes, s.runs));
            st.set_description(failing.join("\n"));
            st
        };
        let mut case = TestCase::new(s.class.clone(), status);
        case.set_classname("campaign");
        case.extra.insert("runs".into(), s.runs.to_string().into());
        suite.add_test_case(case);
    }
    let mut r = Report::new("canstar");
    r.add_test_suite(suite);
    r.to_string().expect("a JUnit report of plain strings serialises")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::campaign::report::RunOutcome;

    fn outcome(class: &str, rep: u32, pass: bool) -> RunOutcome {
        RunOutcome {
            class: class.into(),
            rep,
            seed: 100 + rep as u64,
            pass,
            failures: if pass { vec![] } else { vec!["a healthy controller reached TEC/REC 96 (limit 96)".into()] },
            ..Default::default()
        }
    }

    #[test]
    fn one_case_per_class_and_a_failure_with_the_rerun_command() {
        let runs = vec![outcome("pub01", 0, true), outcome("pub01", 1, true), outcome("hub-flip", 0, true), outcome("hub-flip", 1, false)];
        let classes = [crate::campaign::class("pub01").unwrap(), crate::campaign::class("hub-flip").unwrap()];
        let settings = crate::campaign::Settings { seed: 1, reps: 2, double_delay_bits: 400, engine: Default::default(), hub: None };
        let rep = CampaignReport::new(settings, &classes, None, runs);
        let x = xml(&rep);
        assert!(x.contains(r#"<testsuite name="canstar-campaign" tests="2""#), "{x}");
        assert!(x.contains(r#"failures="1""#), "{x}");
        assert!(x.contains(r#"<testcase name="pub01" classname="campaign""#), "{x}");
        assert!(x.contains("1 of 2 runs failed"), "{x}");
        assert!(x.contains("canstar campaign --class hub-flip --run-seed 101"), "{x}");
        assert_eq!(x.matches("<failure").count(), 1, "{x}");
    }
}
