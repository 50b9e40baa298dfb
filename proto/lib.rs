//! The versioned gRPC API of needlesim (`needlesim.v1`); the protocol definitions arrive with the server issue.
