//! Every example of this crate runs to completion (each in a few seconds on its coarse mesh).

#[path = "../examples/cantilever.rs"]
mod cantilever;
#[path = "../examples/drop.rs"]
mod drop;
#[path = "../examples/gmsh_chamber.rs"]
mod gmsh_chamber;

#[test]
fn cantilever_runs() {
    cantilever::main().unwrap();
}

#[test]
fn drop_runs() {
    drop::main().unwrap();
}

#[test]
fn gmsh_chamber_runs() {
    gmsh_chamber::main().unwrap();
}
