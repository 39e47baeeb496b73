//! The integration tests of isochor-scenes as one test binary (`autotests = false` in its
//! `Cargo.toml`): one link and one copy of the dependencies' generic code instead of one per
//! file. Each module is one file of this folder; `.ci/run` checks that every file is listed.

mod actuators;
mod bodies;
mod bounds;
mod builtin;
mod checkpoints;
mod cli;
mod cloth;
mod common;
mod compare;
mod contact;
mod contact_scenes;
mod explicit_and_interrupt;
mod finger_volume;
mod finger_walls;
mod frames;
mod mesh_obstacles;
mod outputs;
mod overrides;
mod physical;
mod pneunet;
mod preview;
mod regions;
mod study;
mod surface_contact;
mod volume_control;
