// Bundles the viewer page's script (src/main.js and three.js) into one minified file.
// Usage: node build.mjs [OUTFILE]   (default dist/viewer.js). The Rust build (crates/tumble-cli/build.rs)
// calls this with a file in its OUT_DIR and embeds the result in the `tumble` binary.
import { build } from 'esbuild';

const outfile = process.argv[2] ?? 'dist/viewer.js';
await build({
  entryPoints: ['src/main.js'],
  bundle: true,
  minify: true,
  format: 'iife',
  target: ['es2020'],
  legalComments: 'none',
  outfile,
  logLevel: 'warning',
});
