//! The `isochor` command-line program: a thin wrapper over [`isochor_scenes::cli`].

use clap::Parser;
use isochor_scenes::cli::{execute, Cli};
use isochor_scenes::SceneError;

fn main() {
    let cli = Cli::parse();
    let mut stdout = std::io::stdout().lock();
    match execute(cli, &mut stdout) {
        Ok(code) => std::process::exit(code),
        // A closed pipe (`isochor show x | head`) is not an error.
        Err(SceneError::Stdout(e)) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
