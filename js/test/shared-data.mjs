// Where the tests and benchmarks find other projects' example meshes (the Kirra terrain,
// cylinder and cup): ../shared/data beside the repository, not part of it. Tests that
// need them are skipped with `missing` as the reason when the folder is not there.
import { existsSync, readFileSync } from "node:fs";
import { fileURLToPath } from "node:url";

/** The folder, as a file URL (the repository's root is two levels above this file's). */
export const sharedDataUrl = new URL("../../../shared/data/", import.meta.url);

/**
 * false when the Kirra files are there, else the reason to skip what needs them (as
 * node:test's `skip` option takes it: null would skip too).
 */
export const missing = existsSync(new URL("kirra_terrain.obj", sharedDataUrl))
	? false
	: `${fileURLToPath(sharedDataUrl)} not found (other projects' example meshes, kept beside the repository)`;

/** The bytes of a file of the folder. */
export function sharedData(name) {
	return readFileSync(new URL(name, sharedDataUrl));
}
