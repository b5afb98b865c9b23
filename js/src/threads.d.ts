// Types of meshbool/threads: the number of threads of the builds loaded after the call.

/** Asks for `n` threads (1 to 1024; `null`: the default) in the package loaded after this call on this thread. */
export function setThreads(n: number | null): void;
/** The number asked for with `setThreads`, or null. */
export function requestedThreads(): number | null;
