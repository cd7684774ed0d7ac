//! Each object's material index and what its normal is computed from, side
//! by side: read at every hit (and the material at every shadow crossing)
//! without loading the object itself (the objects of an SPD scene fill more
//! than a core's cache, and each such load missed it).

use glam::DVec3;

use super::normals::NormalRecipe;
use crate::object::Object;

#[derive(Clone, Debug)]
pub(crate) struct ObjectTables {
    materials: Vec<usize>,
    normals: Vec<NormalRecipe>,
}

impl ObjectTables {
    pub(crate) fn build(objects: &[Object]) -> ObjectTables {
        ObjectTables {
            materials: objects.iter().map(|o| o.material).collect(),
            normals: objects.iter().map(|o| NormalRecipe::of(&o.shape)).collect(),
        }
    }

    /// `objects[object].material`.
    #[inline]
    pub(crate) fn material(&self, object: usize) -> usize {
        self.materials[object]
    }

    /// `objects[object].shape.geometric_normal(point)`, to the bit.
    #[inline]
    pub(crate) fn geometric_normal(
        &self,
        objects: &[Object],
        object: usize,
        point: DVec3,
    ) -> DVec3 {
        self.normals[object]
            .normal_at(point)
            .unwrap_or_else(|| objects[object].shape.geometric_normal(point))
    }
}
