//! The haptic device bridge; its device loop arrives with the device-bridge issue.

fn main() {
    eprintln!("needlesim-bridge: not implemented yet");
    std::process::exit(2);
}
