# The needlesim server as a container image (issue 22; deploy/k8s/ runs it as an Agones Fleet).
# Two stages: the build (the same binaries as README's `cargo run --release -p needlesim-server`;
# tests/it/fleet.rs checks the two agree), then a slim runtime with the server and the web viewer's
# static files. Build: `docker build -t needlesim/server:0.1.0 .`
#
# The shipped scenes are compiled into the binary; proto/ is compiled by protox (no protoc); TLS is
# rustls with ring (no OpenSSL), so the runtime needs only glibc and CA certificates.

FROM rust:1.95-bookworm AS build
WORKDIR /src
COPY . .
RUN cargo build --release --locked -p needlesim-server

FROM debian:bookworm-slim AS runtime
RUN apt-get update \
    && apt-get install -y --no-install-recommends ca-certificates \
    && rm -rf /var/lib/apt/lists/* \
    && useradd --uid 10001 --user-group --no-create-home --home-dir /data needlesim \
    && mkdir -p /data /app/web \
    && chown needlesim:needlesim /data
COPY --from=build /src/target/release/needlesim-server /usr/local/bin/needlesim-server
COPY --from=build /src/web/index.html /app/web/index.html
COPY --from=build /src/web/dist /app/web/dist
USER 10001
WORKDIR /data
# One port: gRPC, gRPC-web, /metrics and the web viewer.
EXPOSE 50051
ENTRYPOINT ["/usr/local/bin/needlesim-server"]
CMD ["serve", "--listen=0.0.0.0:50051", "--data-dir=/data", "--web-dir=/app/web"]
