//! isochor scenes
