//! The `needlesim` command-line client; its commands arrive with the CLI issue.

fn main() {
    eprintln!("needlesim: the client has no commands yet; use needlesim-server");
    std::process::exit(2);
}
