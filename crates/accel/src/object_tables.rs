//! Each object's material index and what its normal is computed from, side
//! by side: read at every hit (and the material at every shadow crossing)
//! without loading the object itself (the objects of an SPD scene fill more
//! than a core's cache, and each such load missed it). 12 bytes an object.

use glam::DVec3;

use super::Accel;
use super::normals::NormalRecipe;
use raystep_model::object::Object;
use raystep_model::shapes::Shape;

#[derive(Clone, Debug)]
pub struct ObjectTables {
    /// u32, not usize: 4 bytes less an object (a scene has far fewer materials).
    materials: Vec<u32>,
    normals: Vec<NormalRecipe>,
    /// The normals of the `NormalRecipe::Flat` recipes.
    flats: Vec<DVec3>,
}

impl ObjectTables {
    pub fn build(objects: &[Object]) -> ObjectTables {
        let mut flats = Vec::new();
        let normals = objects
            .iter()
            .map(|o| NormalRecipe::of(&o.shape, &mut flats))
            .collect();
        ObjectTables {
            materials: objects
                .iter()
                .map(|o| u32::try_from(o.material).expect("fewer materials than a u32 counts"))
                .collect(),
            normals,
            flats,
        }
    }

    /// `objects[object].material`.
    #[inline]
    pub fn material(&self, object: usize) -> usize {
        self.materials[object] as usize
    }

    /// `objects[object].shape.geometric_normal(point)`, to the bit; `accel`
    /// is the hierarchy built over `objects`.
    #[inline]
    pub fn geometric_normal(
        &self,
        objects: &[Object],
        accel: &Accel,
        object: usize,
        point: DVec3,
    ) -> DVec3 {
        self.normals(objects, accel, object, point).0
    }

    /// `geometric_normal`, and with it a patch's plane normal, which decides
    /// the side a ray meets it from (MODEL §3); `None` for every other
    /// shape, whose side is its N_g's. A hit's one look-up in the tables.
    #[inline]
    pub fn normals(
        &self,
        objects: &[Object],
        accel: &Accel,
        object: usize,
        point: DVec3,
    ) -> (DVec3, Option<DVec3>) {
        match &self.normals[object] {
            NormalRecipe::FromLeaf => (
                accel
                    .leaf_normal(object, point)
                    .unwrap_or_else(|| objects[object].shape.geometric_normal(point)),
                None,
            ),
            NormalRecipe::Flat(index) => (self.flats[*index as usize], None),
            NormalRecipe::SmoothTriangle(triangle) => {
                (triangle.normal_at(point), Some(triangle.flat))
            }
            NormalRecipe::FromShape => {
                let shape = &objects[object].shape;
                let plane = match shape {
                    Shape::Patch(patch) => Some(patch.polygon.plane.normal),
                    _ => None,
                };
                (shape.geometric_normal(point), plane)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_model::shapes::{Cone, Patch, Plane, Polygon, Shape, Sphere};

    #[test]
    fn each_objects_normal_is_its_shapes_to_the_bit() {
        let triangle = vec![
            DVec3::new(0.1, -0.2, 0.3),
            DVec3::new(1.3, 0.2, -0.1),
            DVec3::new(0.2, 0.9, 0.6),
        ];
        let normals = vec![
            DVec3::new(0.2, 0.1, 1.0),
            DVec3::new(-0.3, 0.4, 0.8),
            DVec3::new(0.1, -0.5, 0.9),
        ];
        let square = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let shapes = [
            Shape::Sphere(Sphere::new(DVec3::new(0.2, -0.1, 0.3), 0.7).unwrap()),
            Shape::Plane(Plane::new(DVec3::new(0.3, 1.0, 0.2), DVec3::ZERO).unwrap()),
            Shape::Polygon(Polygon::new(triangle.clone()).unwrap()),
            Shape::Polygon(Polygon::new(square.clone()).unwrap()),
            Shape::Patch(Patch::new(triangle.clone(), normals).unwrap()),
            Shape::Patch(Patch::new(square.clone(), vec![DVec3::Z; 4]).unwrap()),
            Shape::Cone(Box::new(
                Cone::new(DVec3::ZERO, 0.5, DVec3::Z, 0.2).unwrap(),
            )),
        ];
        let objects: Vec<Object> = shapes
            .iter()
            .map(|shape| Object {
                name: "".into(),
                shape: shape.clone(),
                material: 0,
            })
            .collect();
        let accel = Accel::build(&objects);
        let tables = ObjectTables::build(&objects);
        // Which recipe each shape gets: the triangle and the sphere read
        // their leaf records, the plane and the square a flat normal.
        let kinds: Vec<&str> = tables
            .normals
            .iter()
            .map(|recipe| match recipe {
                NormalRecipe::FromLeaf => "from leaf",
                NormalRecipe::Flat(_) => "flat",
                NormalRecipe::SmoothTriangle(_) => "smooth triangle",
                NormalRecipe::FromShape => "from shape",
            })
            .collect();
        assert_eq!(
            kinds,
            [
                "from leaf",
                "flat",
                "from leaf",
                "flat",
                "smooth triangle",
                "from shape",
                "from shape"
            ]
        );
        assert_eq!(tables.flats.len(), 2);
        // Points on and off the triangle (its vertices, edges, inside and
        // outside, where the patch takes the nearest fan triangle).
        let mut compared = 0;
        for (object, shape) in shapes.iter().enumerate() {
            for i in 0..=12 {
                for j in 0..=12 {
                    let (u, v) = (f64::from(i) / 8.0 - 0.25, f64::from(j) / 8.0 - 0.25);
                    let point = triangle[0]
                        + u * (triangle[1] - triangle[0])
                        + v * (triangle[2] - triangle[0]);
                    let expected = shape.geometric_normal(point);
                    let got = tables.geometric_normal(&objects, &accel, object, point);
                    let bits = |n: DVec3| n.to_array().map(f64::to_bits);
                    assert_eq!(bits(got), bits(expected), "{shape:?} at {point}");
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 7 * 13 * 13);
    }
}
