//! A named shape with its material: what a scene lists and the acceleration
//! structure indexes. Apart from `scene` so `accel` can use it without
//! importing the scene that builds it.

use crate::shapes::Shape;

#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    pub name: String,
    pub shape: Shape,
    /// Index into `Scene::materials`.
    pub material: usize,
}
