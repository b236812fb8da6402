//! stuffbit
use super::*;
pub fn run(ctx: &mut Ctx) { let _ = ctx; }
