//! The haptic device bridge binary: a placeholder until the device loop arrives (issue 5, second part).

fn main() {
    eprintln!(
        "needlesim-bridge: not implemented yet. It will attach to a session's device channel \
         (needlesim_bridge::shm::DeviceChannel::attach), write the device pose each device sample, \
         and render the server's force (with its stiffness Jacobian between ticks)."
    );
    std::process::exit(2);
}
