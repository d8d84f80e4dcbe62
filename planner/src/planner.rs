//! Serpentine planning: rows, U-turns, dynamic programming over row ends.
use crate::{Plan, PlanError, PlanOptions, Shape};

pub(crate) fn plan_shape(_shape: &Shape, _opts: &PlanOptions, name: &str) -> Result<Plan, PlanError> {
    Err(PlanError::Unplannable { name: name.into(), reason: "planner not written yet".into() })
}
