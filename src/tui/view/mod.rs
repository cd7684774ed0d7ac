//! What the panes show, worked out apart from drawing: the ray tree's rows,
//! the step list, stepping, the diagram's labels and its pan and zoom, where
//! image pixels land in the image pane, the details' lines, the help's
//! lines, a ray log's marks and lines beside the tree, and where each pane
//! goes. Pure functions of the recording, the scene and sizes, so
//! each file tests its own; the app (`app/`) and the panes (`pane/`) both
//! read them, and nothing here knows either.

pub(crate) mod canvas_lines;
pub(crate) mod cell_labels;
pub mod details;
pub(crate) mod find;
pub(crate) mod help;
pub(crate) mod image_grid;
pub(crate) mod layout;
pub(crate) mod mistakes_menu;
pub(crate) mod pan_zoom;
pub mod steps;
pub mod tree;
pub(crate) mod your_rays;
