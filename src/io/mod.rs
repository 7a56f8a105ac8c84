//! Reading and writing scenes and golden files (formats in golden/FORMAT.md).

pub mod golden;
pub mod scene_json;
