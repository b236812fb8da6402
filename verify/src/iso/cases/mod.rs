//! The ISO 16845-1 cases implemented on the lower tester, one file per case
//! (see each file's documentation for the clause and what it checks).

use super::IsoCase;

pub fn all() -> Vec<IsoCase> {
    vec![]
}
