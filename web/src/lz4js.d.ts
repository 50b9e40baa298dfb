//! Type declarations for lz4js 0.2.0, which ships none: the one function the viewer uses.
declare module "lz4js" {
  /**
   * Decompresses an LZ4 frame. `maxSize` is the decompressed size when known (else it is read
   * from the frame); the result is a Uint8Array (a plain array only where typed arrays are
   * missing).
   */
  export function decompress(src: Uint8Array, maxSize?: number): Uint8Array | number[];
}
