// The reference library's own tests (trimesh-boolean v0.5.6, MIT, see LICENSE here), run
// unchanged but for the import path against this package: `npm run test:compat`.
import { defineConfig } from "vitest/config";
import { fileURLToPath } from "node:url";

export default defineConfig({
	test: {
		root: fileURLToPath(new URL(".", import.meta.url)),
		include: ["*.test.js"],
		testTimeout: 30000,
	},
});
