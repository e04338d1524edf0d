/**
 * A model of what makes SwiftShader's shader compile slow, for the
 * compile-cost test (test/browser/shader-compile-cost.test.ts): the work of
 * SpirvShader's ExistsPath, run for every loop header while SwiftShader
 * emits a shader (is each incoming edge a back edge?). Its breadth-first
 * search marks a block seen only when it is taken from the queue, so a block
 * is queued once per path that reaches it first: the work doubles with every
 * if/else in sequence inside a loop (bench/results/compile-time-2026-12-06.md,
 * measured: 2.6 s of compile for 24 if/elses in one loop, 0.05 s for 24 ifs).
 *
 * Input: the SPIR-V that ANGLE makes of a GLSL ES shader (WEBGL_debug_shaders
 * gives it with --enable-privileged-webgl-extensions). SwiftShader inlines
 * every call before it emits (spirv-opt); so does this model, each call site
 * a copy of the callee whose returns all lead to the code after the call.
 */

const OP = {
  Name: 5,
  Function: 54,
  FunctionEnd: 56,
  FunctionCall: 57,
  LoopMerge: 246,
  SelectionMerge: 247,
  Label: 248,
  Branch: 249,
  BranchConditional: 250,
  Switch: 251,
  Kill: 252,
  Return: 253,
  ReturnValue: 254,
  Unreachable: 255,
  TerminateInvocation: 4416,
} as const;

const TERMINATORS = new Set<number>([OP.Kill, OP.Return, OP.ReturnValue, OP.Unreachable, OP.TerminateInvocation]);

/** A block of a function, cut at each call: segment k ends with call k (to the function `calls[k]`). */
interface Block {
  id: number;
  calls: number[];
  successors: number[];
  loopMerge: number | null;
  /** Its second branch target is not its selection merge either: an if/else (a "diamond"). */
  ifElse: boolean;
  returns: boolean;
}

interface SpirvFunction {
  id: number;
  entry: number;
  blocks: Map<number, Block>;
}

export interface SpirvModule {
  names: Map<number, string>;
  functions: Map<number, SpirvFunction>;
  entryPoint: number;
}

function readString(words: Uint32Array, start: number, end: number): string {
  const bytes: number[] = [];
  for (let i = start; i < end; i++) {
    for (let b = 0; b < 4; b++) {
      const byte = (words[i] >>> (8 * b)) & 0xff;
      if (byte === 0) return String.fromCharCode(...bytes);
      bytes.push(byte);
    }
  }
  return String.fromCharCode(...bytes);
}

/** Parses the functions, blocks, branches and calls of a SPIR-V module. */
export function parseSpirv(words: Uint32Array): SpirvModule {
  if (words[0] !== 0x07230203) throw new Error('not SPIR-V (bad magic number)');
  const names = new Map<number, string>();
  const functions = new Map<number, SpirvFunction>();
  let fn: SpirvFunction | null = null;
  let block: Block | null = null;
  let selectionMerge: number | null = null;
  let entryPoint = -1;
  for (let i = 5; i < words.length; ) {
    const count = words[i] >>> 16;
    const op = words[i] & 0xffff;
    if (count === 0) throw new Error(`malformed SPIR-V at word ${i}`);
    const operand = (k: number) => words[i + 1 + k];
    if (op === 15 /* OpEntryPoint */) entryPoint = operand(1);
    else if (op === OP.Name) names.set(operand(0), readString(words, i + 2, i + count));
    else if (op === OP.Function) {
      fn = { id: operand(1), entry: -1, blocks: new Map() };
      functions.set(fn.id, fn);
    } else if (op === OP.FunctionEnd) fn = null;
    else if (fn && op === OP.Label) {
      block = { id: operand(0), calls: [], successors: [], loopMerge: null, ifElse: false, returns: false };
      fn.blocks.set(block.id, block);
      if (fn.entry < 0) fn.entry = block.id;
    } else if (block) {
      if (op === OP.FunctionCall) block.calls.push(operand(2));
      else if (op === OP.LoopMerge) block.loopMerge = operand(0);
      else if (op === OP.SelectionMerge) selectionMerge = operand(0);
      else if (op === OP.Branch) block.successors.push(operand(0));
      else if (op === OP.BranchConditional) {
        block.successors.push(operand(1), operand(2));
        block.ifElse = selectionMerge !== null && operand(1) !== selectionMerge && operand(2) !== selectionMerge;
      } else if (op === OP.Switch) {
        block.successors.push(operand(1));
        for (let k = 3; k < count - 1; k += 2) block.successors.push(operand(k));
      } else if (TERMINATORS.has(op)) block.returns = true;
      if (op === OP.Branch || op === OP.BranchConditional || op === OP.Switch || TERMINATORS.has(op)) {
        block.successors = [...new Set(block.successors)];
        block = null;
        selectionMerge = null;
      }
    }
    i += count;
  }
  if (!functions.has(entryPoint)) throw new Error('no entry point function');
  return { names, functions, entryPoint };
}

/** The if/else constructs of each function, by name: what to rewrite with pick() when the cost is over. */
export function ifElseCounts(module: SpirvModule): Map<string, number> {
  const counts = new Map<string, number>();
  for (const fn of module.functions.values()) {
    const n = [...fn.blocks.values()].filter((b) => b.ifElse).length;
    if (n > 0) counts.set(module.names.get(fn.id) ?? `%${fn.id}`, n);
  }
  return counts;
}

/** The inlined control-flow graph: successors per node, and each loop header's merge node. */
interface Graph {
  successors: number[][];
  loops: { header: number; merge: number }[];
}

/** Inlines every call from the entry point into one graph (recursion is not allowed in GLSL). */
function inline(module: SpirvModule, maxNodes: number): Graph {
  const successors: number[][] = [];
  const loops: Graph['loops'] = [];
  const node = () => {
    if (successors.length >= maxNodes) throw new Error(`more than ${maxNodes} blocks after inlining`);
    successors.push([]);
    return successors.length - 1;
  };
  // An instance of fn: its entry node; each returning block's last node goes to `after`.
  const instantiate = (fnId: number, after: number | null): number => {
    const fn = module.functions.get(fnId);
    if (!fn) throw new Error(`call of an unknown function %${fnId}`);
    const first = new Map<number, number>(); // block id -> its first node
    for (const b of fn.blocks.values()) first.set(b.id, node());
    for (const b of fn.blocks.values()) {
      let current = first.get(b.id)!;
      for (const callee of b.calls) {
        const next = node();
        successors[current].push(instantiate(callee, next));
        current = next;
      }
      for (const s of b.successors) successors[current].push(first.get(s)!);
      if (b.returns && after !== null) successors[current].push(after);
      if (b.loopMerge !== null) loops.push({ header: first.get(b.id)!, merge: first.get(b.loopMerge)! });
    }
    return first.get(fn.entry)!;
  };
  instantiate(module.entryPoint, null);
  return { successors, loops };
}

/**
 * The queue pops of SwiftShader's ExistsPath(from, to, notPassingThrough)
 * (duplicates queued, a block marked seen when taken), stopping at `limit`.
 */
function existsPathPops(graph: Graph, from: number, to: number, notPassingThrough: number, limit: number): number {
  const seen = new Uint8Array(graph.successors.length);
  seen[notPassingThrough] = 1;
  let queue = [from];
  let pops = 0;
  while (queue.length > 0) {
    const next: number[] = [];
    for (const id of queue) {
      if (++pops >= limit) return pops;
      for (const out of graph.successors[id]) {
        if (seen[out]) continue;
        if (out === to) return pops;
        next.push(out);
      }
      seen[id] = 1;
    }
    queue = next;
  }
  return pops;
}

/**
 * The modelled compile cost: ExistsPath's pops summed over every loop
 * header and each of its incoming edges (what ForeachBlockDependency and
 * EmitLoop ask), capped at `limit`.
 */
export function compileCost(module: SpirvModule, limit = 1e8): number {
  const graph = inline(module, 1_000_000);
  const predecessors: number[][] = graph.successors.map(() => []);
  graph.successors.forEach((outs, id) => outs.forEach((out) => predecessors[out].push(id)));
  let total = 0;
  for (const { header, merge } of graph.loops) {
    for (const dep of predecessors[header]) {
      total += existsPathPops(graph, header, dep, merge, limit - total);
      if (total >= limit) return total;
    }
  }
  return total;
}
