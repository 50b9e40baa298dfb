//! The server's gRPC API over gRPC-web (connect-web clients on the page's own origin) and the
//! session tokens the page knows.
import { createClient, type Client } from "@connectrpc/connect";
import { createGrpcWebTransport } from "@connectrpc/connect-web";
import { ControlService, ObserveService, RecordingService, SessionService } from "./gen/needlesim/v1/needlesim_pb";
import { TrainingService } from "./gen/needlesim/v1/training_pb";

const transport = createGrpcWebTransport({ baseUrl: window.location.origin, useBinaryFormat: true });

export const sessions: Client<typeof SessionService> = createClient(SessionService, transport);
export const control: Client<typeof ControlService> = createClient(ControlService, transport);
export const observe: Client<typeof ObserveService> = createClient(ObserveService, transport);
export const recordings: Client<typeof RecordingService> = createClient(RecordingService, transport);
export const training: Client<typeof TrainingService> = createClient(TrainingService, transport);

/** Call options carrying a session's controller or observer token. */
export function auth(token: string): { headers: Record<string, string> } {
  return { headers: { authorization: `Bearer ${token}` } };
}

/** Tokens the page knows, by session id (from sessions it created, or pasted / in the URL). */
export const tokens = new Map<string, string>();
