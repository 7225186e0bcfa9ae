//! Scenes assemble a case into a model, advance it, and describe each step as a [`crate::frame::Frame`] for
//! the sinks. A scene computes for a frame only what the sinks asked for ([`crate::frame::Needs`]).

pub mod block;
pub mod body;
pub mod drawing;
pub mod dynamic;
pub mod interface;
pub mod mesh;
pub mod point;
pub mod sample;
pub mod spring_block;

use crate::case::{Case, SceneSpec};
pub use crate::scene::interface::{RunError, Scene, SceneMemory};

/// Builds the scene a case describes.
pub fn build(case: &Case) -> Result<Box<dyn Scene>, RunError> {
    Ok(match &case.scene {
        SceneSpec::Point(spec) => Box::new(point::PointScene::new(case.friction.clone(), spec.clone())),
        SceneSpec::SpringBlock(spec) => Box::new(spring_block::SpringBlockScene::new(case, spec)?),
        SceneSpec::Block(spec) => Box::new(block::BlockScene::new(case, spec)?),
        SceneSpec::Mesh(spec) => Box::new(mesh::scene(case, spec)?),
    })
}
