//! Named factors: when yours is a constant times ours, which of the ray's
//! own numbers that constant is (1/d_L², k_d / k_a, the ray's weight, ...).

use super::close_numbers;
use crate::divergence::moment::Field;
use crate::divergence::ours::OurRays;
use crate::raylog::Step;
use raystep_engine::record::{Node, num};

/// Named factors a difference of `field` may be, with their values.
pub(super) fn candidates(ours: &OurRays, ray: usize, field: Field) -> Vec<(String, f64)> {
    let node = ours.node(ray);
    let mut named = Vec::new();
    let hit = node.hit.as_ref();
    match field {
        Field::Diffuse(i) | Field::Specular(i) => {
            if let Some(light) = node.lights.iter().find(|l| l.light_index == i) {
                // A directional light has no d_L (MODEL §4) to scale by.
                if let Some(d) = light.distance {
                    named.push((format!("1/d_L² (d_L = {})", num(d)), 1.0 / (d * d)));
                    named.push((format!("1/d_L (d_L = {})", num(d)), 1.0 / d));
                }
                named.push((
                    format!("1/f_att (f_att = {})", num(light.f_att)),
                    1.0 / light.f_att,
                ));
                named.push((format!("N·L = {}", num(light.n_dot_l)), light.n_dot_l));
                named.push((
                    format!("1/(N·L) (N·L = {})", num(light.n_dot_l)),
                    1.0 / light.n_dot_l,
                ));
                if let Some(shadow) = &light.shadow {
                    named.push((format!("1/S (S = {})", num(shadow.s)), 1.0 / shadow.s));
                }
                // N·(L + V) = |L + V| N·H: H left unnormalised, to the n.
                if let (Field::Specular(_), Some(hit)) = (field, hit) {
                    let sum = light.to_light + (-node.direction).normalize_or_zero();
                    let n = hit.factors.n;
                    named.push((
                        format!(
                            "H not normalised (×|L+V|^n: |L+V| = {}, n = {}): H = normalize(L + V) \
                             (MODEL §4)",
                            num(sum.length()),
                            num(n)
                        ),
                        sum.length().powf(n),
                    ));
                }
                // N·L with L = P_L − p is d_L times N·L with L normalised.
                if let (Field::Diffuse(_), Some(d)) = (field, light.distance) {
                    named.push((format!("d_L = {}: L = P_L − p not normalised", num(d)), d));
                }
            }
            if let Some(hit) = hit {
                let k = if matches!(field, Field::Diffuse(_)) {
                    hit.factors.kd
                } else {
                    hit.factors.ks
                };
                named.push((format!("the k once more ({})", num(k)), k));
                named.push((format!("1/k (k = {}): k left out", num(k)), 1.0 / k));
            }
        }
        Field::Ambient => {
            if let Some(hit) = hit {
                let f = hit.factors;
                named.push((
                    format!(
                        "k_d / k_a = {} / {}: k_d where k_a belongs",
                        num(f.kd),
                        num(f.ka)
                    ),
                    f.kd / f.ka,
                ));
                named.push((
                    format!("1/k_a (k_a = {}): k_a left out", num(f.ka)),
                    1.0 / f.ka,
                ));
            }
            for light in &node.lights {
                named.push((
                    format!(
                        "f_att applied to the ambient (f_att = {} for light {}): MODEL §4's \
                         ambient term I_a O_d takes no f_att",
                        num(light.f_att),
                        light.light_index
                    ),
                    light.f_att,
                ));
            }
        }
        Field::Color => {
            named.push((
                format!("the ray's weight {}", num(node.weight)),
                node.weight,
            ));
            named.push((
                format!("the attenuation {}", num(node.attenuation)),
                node.attenuation,
            ));
            named.push((
                format!(
                    "the ray's weight × attenuation {}",
                    num(node.weight * node.attenuation)
                ),
                node.weight * node.attenuation,
            ));
        }
        Field::Weight => {
            // A reflected ray's weight is k_s, or k_s + k_t at total
            // internal reflection (MODEL §5): one where the other belongs.
            let parent = ours.source(ray).and_then(|p| p.hit.as_ref());
            if let (Some(Step::Reflected), Some(parent)) =
                (ours.rays()[ray].path.steps.last(), parent)
            {
                let (ks, kt) = (parent.factors.ks, parent.factors.kt);
                let tir = ours.source(ray).is_some_and(Node::tir);
                let (factor, words) = if tir {
                    (
                        ks / (ks + kt),
                        "k_s alone where total internal reflection gives k_s + k_t (MODEL §5)",
                    )
                } else {
                    (
                        (ks + kt) / ks,
                        "k_s + k_t, the weight of total internal reflection, where ours has k_s and no TIR",
                    )
                };
                named.push((
                    format!("{words}; k_s = {}, k_t = {}", num(ks), num(kt)),
                    factor,
                ));
            }
        }
        Field::T => {
            let d = node.direction.length();
            named.push((format!("1/|dir| (|dir| = {})", num(d)), 1.0 / d));
        }
        _ => {}
    }
    named.retain(|(_, value)| value.is_finite() && *value != 0.0);
    named
}

pub(super) fn scaled_words(factor: f64, named: &[(String, f64)]) -> String {
    match named
        .iter()
        .find(|(_, value)| close_numbers(factor, *value))
    {
        Some((name, _)) => format!("yours is {} × ours: {name}", num(factor)),
        None => format!("yours is {} × ours", num(factor)),
    }
}
