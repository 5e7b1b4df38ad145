//! The `rootclip` command line; see `rootclip --help` and the README.

fn main() -> std::process::ExitCode {
    rootclip::cli::main()
}
