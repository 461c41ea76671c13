//! No shadows: every light reaches every point, unweighted. The reference the
//! shadow methods are told from, and the frame a method's cost is measured against.

use crate::scene::LightKind;
use crate::settings::ShadowMethod;

/// The registry's entry: every light, none shadowed.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::None,
    name: "none",
    entry: None,
    handles: "no shadows",
    lights: &LightKind::ALL,
    counts: None,
    budget: super::no_budget,
    warnings: super::no_warnings,
    prepare: |_, _, _, _| None,
};
