// The exported .glb files pass the Khronos glTF validator with no errors (and no warnings).
// Run by ../run_tests.sh, which exports the files (TUMBLE_GLB_FILES, comma-separated).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import validator from 'gltf-validator';

const files = (process.env.TUMBLE_GLB_FILES || '').split(',').filter(Boolean);

for (const file of files) {
  test(`glTF validator: ${path.basename(file)}`, async () => {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(bytes, { maxIssues: 50, uri: path.basename(file) });
    const { numErrors, numWarnings, messages } = report.issues;
    const listed = messages.map((m) => `${m.severity === 0 ? 'error' : m.severity === 1 ? 'warning' : 'info'} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
    assert.equal(numErrors, 0, listed.join('\n'));
    assert.equal(numWarnings, 0, listed.join('\n'));
    assert.ok(report.info.animationCount >= 1, 'the file has an animation');
  });
}
