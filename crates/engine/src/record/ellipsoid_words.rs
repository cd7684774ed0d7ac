//! The words for an ellipsoid's working (MODEL §3): a sphere's quadratic,
//! said to be solved in the sphere's own space, and the normal carried back
//! by the inverse transpose. `inspect`, the debugger's panes and `explain`
//! share them.

use super::numbers::{num, vector};
use raystep_model::shapes::EllipsoidWorking;

/// Where the quadratic is solved and its coefficients: three lines.
pub(crate) fn quadratic_lines(w: &EllipsoidWorking) -> Vec<String> {
    let q = &w.quadratic;
    vec![
        "ellipsoid: a sphere under a transform M, solved in the sphere's own space \
         (the ray moved by M⁻¹, d' not renormalised, so t is the same in both)"
            .to_string(),
        format!(
            "o' = M⁻¹ o = {}, d' = M⁻¹ d = {}; the sphere there: c = {}, r = {}",
            vector(w.object_origin),
            vector(w.object_direction),
            vector(w.object_center),
            num(w.object_radius)
        ),
        format!(
            "A = |d'|^2 = {}, B = 2 d'·(o' - c) = {}, C = |o' - c|^2 - r^2 = {}, discriminant B^2 - 4AC = {}",
            num(q.a),
            num(q.b),
            num(q.c),
            num(q.discriminant)
        ),
    ]
}

/// At a hit, the normal's working: "N_g = normalize(M⁻ᵀ (p' - c)/r) = …".
pub(crate) fn normal_line(w: &EllipsoidWorking) -> Option<String> {
    let (p, n, normal) = (w.object_point?, w.object_normal?, w.normal?);
    Some(format!(
        "normal: p' = M⁻¹ p = {}, (p' - c)/r = {}; N_g = normalize(M⁻ᵀ (p' - c)/r) = {}",
        vector(p),
        vector(n),
        vector(normal)
    ))
}

/// `explain`'s sentence for a hit on an ellipsoid.
pub(crate) fn explained(w: &EllipsoidWorking) -> Option<String> {
    let (p, n, normal) = (w.object_point?, w.object_normal?, w.normal?);
    Some(format!(
        "It is a sphere (centre {}, radius {}) under a transform M: the ray was moved into the \
         sphere's own space by M⁻¹ (o' = {}, d' = {}) and met the sphere there at the same t, at \
         p' = {}; the sphere's normal there, (p' - c)/r = {}, carried back by the inverse \
         transpose, is N_g = normalize(M⁻ᵀ (p' - c)/r) = {}.",
        vector(w.object_center),
        num(w.object_radius),
        vector(w.object_origin),
        vector(w.object_direction),
        vector(p),
        vector(n),
        vector(normal)
    ))
}
