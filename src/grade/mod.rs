//! `raystep grade`: a whole class's renders graded against an assignment's
//! scenes. `model` holds what was found, the one value every output is
//! written from; `html` writes the class report from it.

pub(crate) mod html;
pub(crate) mod model;
