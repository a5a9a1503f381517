#include "commands.h"

#include "batch.h"
#include "stylized_output.h"

namespace motionstyle::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"info", "describe BVH files (joints, frames, fps, units, mapping, contacts) or network files",
       "usage: motionstyle-cli info FILE... [--json] [--mapping MAP.json] [--unit UNIT] [--loss-network LOSS]\n"
       "       motionstyle-cli info CLIP.bvh --write-mapping MAP.json\n\n"
       "Prints what MotionStyle reads from each BVH file (a folder: every .bvh below it): joints, frames, frame rate, the up axis and\n"
       "length unit it assumed, the mapping to the 21 canonical joints, a foot-contact summary and how\n"
       "familiar the clip is to the networks (the loss network's reconstruction error: familiar up to\n"
       "1.5 cm, unusual up to 2.5 cm, far beyond: results will be weak; adapt the networks to such clips).\n"
       "For a network file (train-loss-network, train-style): its kind, shapes, representation, training settings,\n"
       "style clips and loss history, and the file's format version and weight precision (f32/f16, see pack).\n"
       "A skeleton-only BVH (Frames: 0) is described as far as a skeleton goes (joints, mapping); the\n"
       "commands that need motion (convert --fps, cleanup, stylize, transfer) refuse it with exit code 2.\n\n"
       "  --json            print JSON instead of text\n"
       "  --mapping FILE    use this joint-mapping JSON instead of the automatic mapping\n"
       "  --write-mapping FILE\n"
       "                    write the automatic mapping of CLIP's rig as a mapping file to complete by hand\n"
       "                    (the joints it could not find are empty; the rig's joints are listed in it)\n"
       "  --unit UNIT       the file's length unit: cm, m, mm, inch, ft, dm or cmu (default: guessed)\n"
       "  --loss-network LOSS\n"
       "                    the loss network that judges how familiar the clip is (default: the shipped\n"
       "                    one): its reconstruction error, read as familiar, unusual or far\n",
       runInfo},
      {"convert", "read a BVH file, optionally resample it, write it",
       "usage: motionstyle-cli convert IN.bvh OUT.bvh [--fps N]\n\n"
       "Reads IN, resamples it to N frames per second if --fps is given (slerp for rotations, linear\n"
       "for positions), and writes OUT atomically with the same hierarchy and channel layout.\n",
       runConvert},
      {"train-loss-network", "train the loss network on a motion database",
       "usage: motionstyle-cli train-loss-network --data DIR... --out FILE [--epochs N] [--seed S] [--batch B] [--lr LR]\n"
       "                                [--threads T] [--resume] [options]\n\n"
       "Trains the paper's loss network L (eq. 1-3: 66 -> 256 units, width 25, max-pool 2) on 240-frame\n"
       "windows (step 120) at 60 fps of every .bvh under the given folders (recursively) or files, and\n"
       "writes a network file with its normalisation statistics. A checkpoint is written after every epoch\n"
       "(FILE.checkpoint and FILE.checkpoint.state); Ctrl-C stops within a second and keeps it.\n\n"
       "  --data DIR|FILE   training clips (repeatable; more may follow as plain arguments)\n"
       "  --out FILE        the network file to write (atomically, when training completes)\n"
       "  --epochs N        epochs (default 40)\n"
       "  --seed S          seed for initialisation, shuffling and dropout (default 1); same seed and\n"
       "                    thread count give identical networks\n"
       "  --batch B         windows per step (default 16)\n"
       "  --lr LR           Adam learning rate (default 0.0005; warm-up over the first 100 steps)\n"
       "  --lr-schedule S   cosine (default: decays to 1% of --lr over the run) or constant\n"
       "  --clip K          scale a batch's gradient down to K x its expected norm (default 3; 0 = off):\n"
       "                    one batch of extreme windows (fast spins) cannot throw the network off\n"
       "  --threads T       compute threads (default: all cores, at most 8)\n"
       "  --resume          continue from the checkpoint (same data and settings)\n"
       "  --init NET        warm start from an existing loss network (its weights and normalisation)\n"
       "  --checkpoint FILE checkpoint path (default FILE.checkpoint)\n"
       "  --keep-checkpoints keep the checkpoint (FILE.checkpoint and its .state) after a completed run\n"
       "                    (default: removed once FILE is written; an interrupted run always keeps it)\n"
       "  --holdout N       keep every N-th clip (sorted by path) out of training, for eval; listed at the end\n"
       "  --skip-bad        skip unreadable or unmappable files found in folders (default: stop on them)\n"
       "  --unit UNIT       length unit of the clips (cm, m, mm, inch, ft, dm, cmu; default: guessed)\n"
       "  --hidden H        hidden units (default 256)\n"
       "  --sparsity A      L1 weight of eq. 3 on the mean |w| (default 0)\n"
       "  --dropout P       input dropout while training (default 0: a denoising network cannot reconstruct\n"
       "                    other studios' clips)\n"
       "  --foot F          weight of eq. 7 (planted feet stay planted) on the reconstruction, per cm^2\n"
       "                    (default 0): the projection then keeps the clips' foot contacts\n"
       "  --augment A       train on randomly varied copies of the clips every epoch, as clips of other\n"
       "                    studios, actors and rigs vary: on (the default: girdle=75,offsets=20,mirror=0.5),\n"
       "                    off, or changes to the default: girdle=DEG (hip, shoulder and toe joints'\n"
       "                    placement turned by up to DEG), offsets=DEG (the other joints'), proportions=J\n"
       "                    (bone lengths x 1+-J), warp=W (speed x 1/W..W), mirror=P (left/right swapped\n"
       "                    with probability P)\n",
       runTrainLossNetwork, "train-ae"},
      {"train-style", "train a style network (transformation network) for one style",
       "usage: motionstyle-cli train-style [--loss-network LOSS] --content DIR... --style CLIP.bvh [--style LABEL=CLIP.bvh ...]\n"
       "                                   --out FILE [--weights content=1,style=100,foot=F,bone=B,traj=R]\n"
       "                                   [--epochs N | --quick] [--init NET] [--seed S] [--lr LR] [--resume] [options]\n\n"
       "Trains the transformation network T (3 convolutions, 128 units, width 25) so that T(content) keeps\n"
       "the content (eq. 4) in the style of the style clip (eq. 5), with no foot sliding (eq. 7), constant\n"
       "bone lengths (eq. 8) and the content's trajectory (eq. 9), measured through the loss network LOSS.\n\n"
       "Pairing: each content clip is paired with the style clip of its content label, read from file names\n"
       "(dataset-2_walk_elderly_001.bvh: content 'walk', style 'elderly'; other names: the first word, e.g.\n"
       "walk_fast.bvh: 'walk'). A plain --style CLIP pairs by its own label and is the default for labels\n"
       "without a clip; --style LABEL=CLIP pairs that label explicitly. Labels left without a style clip\n"
       "are an error that lists them. Without --style, --init NET retrains NET with the style targets it\n"
       "stores (networks from this version on), e.g. against a loss network adapted to your clips (adapt).\n\n"
       "  --loss-network LOSS  the trained loss network (train-loss-network; default: the shipped one)\n"
       "  --content DIR|FILE  content clips (repeatable; more may follow as plain arguments)\n"
       "  --style [LABEL=]CLIP  style clip(s), at least 25 frames at 60 fps (repeatable)\n"
       "  --out FILE          the style network file (embeds the loss network)\n"
       "  --weights LIST      loss weights, any subset (defaults content=1,style=100,foot=0.03,bone=0.03,traj=0.01)\n"
       "  --init NET          warm start from an existing style network (adjust the weights and retrain; a\n"
       "                      shipped network's name works)\n"
       "  --augment A         train on randomly varied copies of the content every epoch: on (the default:\n"
       "                      offsets=20,mirror=0.5), off, or changes to it as for train-loss-network\n"
       "  --epochs N          epochs (default 100)\n"
       "  --quick             6 epochs: a usable style in about 10 s from one clip (the full 100 refine it)\n"
       "  --lr LR             Adam learning rate (default 0.001; warm-up over the first 100 steps)\n"
       "  --hidden H          hidden units (default 128)\n"
       "  --seed S, --batch B, --lr-schedule S, --clip K, --threads T, --resume, --checkpoint FILE,\n"
       "  --keep-checkpoints, --holdout N, --skip-bad, --unit UNIT: as for train-loss-network\n",
       runTrainStyle},
      {"adapt", "fine-tune the loss network on your own clips (other studios, actors, rigs)",
       "usage: motionstyle-cli adapt [--loss-network LOSS] --data DIR... --out FILE [--epochs N] [--lr LR]\n"
       "                             [--replay DIR...] [--memory FILE|none] [--train-encoder] [options]\n\n"
       "Fine-tunes the loss network LOSS on your clips (no labels needed) so that it reconstructs them: the\n"
       "manifold projection then keeps their content, and 'info' reads them as familiar. By default only\n"
       "the decoder learns and the encoder is kept, so every style network keeps its style targets:\n"
       "retrain one against FILE on your clips with 'train-style --loss-network FILE --init STYLE --content DIR'.\n"
       "Nothing it knew is forgotten: its reconstruction memory (shipped with the loss network) stands in for\n"
       "the clips it learnt from, or --replay mixes them in. Prints how familiar each clip was before and\n"
       "after. A checkpoint is written every epoch; Ctrl-C stops within a second and keeps it.\n\n"
       "  --loss-network LOSS\n"
       "                     the loss network to adapt (a file; default: loss_network, the shipped one)\n"
       "  --data DIR|FILE    your clips (repeatable; more may follow as plain arguments)\n"
       "  --out FILE         the adapted loss network (records what it was adapted on)\n"
       "  --epochs N         epochs (default 200)\n"
       "  --lr LR            Adam learning rate at the start, cosine decay (default 0.0005)\n"
       "  --replay DIR|FILE  clips of the original training data to mix in, so nothing is forgotten\n"
       "  --replay-ratio R   replay frames per frame of yours (default 1)\n"
       "  --memory FILE|none the loss network's reconstruction memory (remember): its training clips kept\n"
       "                     without the clips themselves (default: LOSS's .memory beside it, else the\n"
       "                     shipped one, when it fits LOSS's encoder; none: off)\n"
       "  --memory-weight W  the memory's clips count as W times your frames (default 10)\n"
       "  --train-encoder    let the encoder learn too (style networks then need their style clips again)\n"
       "  --seed S, --threads T, --checkpoint FILE, --keep-checkpoints, --skip-bad, --unit UNIT: as for\n"
       "  train-loss-network\n",
       runAdapt},
      {"remember", "write a loss network's reconstruction memory of the clips it learnt from (for adapt)",
       "usage: motionstyle-cli remember [--loss-network LOSS] --data DIR... --out FILE.memory [--holdout N]\n\n"
       "Encodes the clips with LOSS and writes what its decoder must go on reconstructing: the hidden units'\n"
       "second moments over time and against the clips (core/style/reconstruction_memory.h), a few MB\n"
       "however many clips. adapt then keeps what LOSS reconstructs of them without the clips themselves.\n"
       "Write it beside LOSS (LOSS.net -> LOSS.memory) for adapt to find it.\n\n"
       "  --loss-network LOSS  the loss network (a file; default: loss_network, the shipped one)\n"
       "  --data DIR|FILE      the clips it learnt from (repeatable)\n"
       "  --out FILE           the memory file (written atomically)\n"
       "  --holdout N          leave out every N-th file, as train-loss-network --holdout N did (default 0)\n"
       "  --description TEXT   what it remembers, recorded in the file and in adapted networks\n"
       "  --precision P        f16 (default: half the size) or f32\n"
       "  --threads T, --skip-bad, --unit UNIT: as for train-loss-network\n",
       runRemember},
      {"stylize", "apply a trained style network to a clip",
       "usage: motionstyle-cli stylize --net NET [--loss-network LOSS] IN.bvh --out OUT.bvh [--strength S]\n"
       "                              [--no-cleanup] [--metrics FILE.json] [--fps N]\n"
       "       motionstyle-cli stylize --net NET CLIPS... --out FOLDER [--metrics FOLDER] [--jobs N] [...]\n\n"
       "Runs the style network on the whole clip (any length, no seams), projects the result onto the\n"
       "loss network's motion manifold (decode(encode(.))) with IN's detected foot contacts planted there\n"
       "(the feet stand still through them under the output's path), cleans it up with IK onto IN's own\n"
       "skeleton and writes OUT atomically. Foot contacts saved beside IN (IN.bvh.contacts.json, as the app's\n"
       "Save Contact Tracks writes them) decide where the clean-up locks the feet, as in cleanup. Every\n"
       "contact is held unless the style moved that step more than 20 cm (the foot then follows the\n"
       "network; a contact forced on in the saved tracks is held anyway); the cleaned skate is over them.\n\n"
       "  --net NET       the style network (train-style), or a shipped network's name (see models)\n"
       "  --loss-network LOSS\n"
       "                  optional: checked to be the loss network NET was trained against\n"
       "  --strength S    0 = the content unchanged, 1 = fully styled (default 1), blended in feature space\n"
       "  --refine-steps N\n"
       "                  steps of the network's own objective (eq. 10's content and style terms) on this\n"
       "                  clip after the network (default 30, 0 = the network's output as it is): clips\n"
       "                  unlike the network's training data get the style it gives its own\n"
       "  --unit UNIT     IN's length unit (default: guessed)\n" MOTIONSTYLE_OUTPUT_OPTIONS_HELP MOTIONSTYLE_BATCH_HELP,
       runStylize},
      {"transfer", "style transfer by optimisation (Holden et al. 2016), no style network needed",
       "usage: motionstyle-cli transfer [--loss-network LOSS] --style CLIP.bvh IN.bvh --out OUT.bvh [--iterations N]\n\n"
       "Optimises the loss network's hidden units so that the decoded motion keeps IN's content and takes\n"
       "the style clip's Gram matrix (Adam, lr 0.01), starting from IN's own hidden units, then runs a\n"
       "constraint pass (feet, bone lengths, trajectory). OUT as for stylize (IK clean-up by default).\n"
       "Prints how much style was added: the style distance to the clip before and after (eval's).\n\n"
       "The weights: content (1) keeps IN's hidden units, style (--style-weight) pulls their Gram matrix\n"
       "to the style clip's; both are renormalised to sum 1. The constraint pass adds planted feet, bone\n"
       "lengths and IN's root velocities at 0.1 per cm^2 each.\n\n"
       "  --iterations N             style iterations (default 250)\n"
       "  --constraint-iterations N  constraint iterations (default 100)\n"
       "  --style-weight S           style weight against content 1 (default 30: a style distance ratio of\n"
       "                             0.2-0.4 on held-out walks; 1 barely moves a walk)\n"
       "  --lr LR                    Adam learning rate (default 0.01)\n"
       "  --noise-start              start from noise like the 2016 code (for comparison)\n"
       "  --unit UNIT                length unit of the clips (default: guessed)\n" MOTIONSTYLE_OUTPUT_OPTIONS_HELP,
       runTransfer},
      {"cleanup", "IK clean-up of a clip on its own skeleton: feet locked, bones exact, on the floor",
       "usage: motionstyle-cli cleanup IN.bvh --out OUT.bvh [--contacts FILE] [--metrics FILE.json]\n"
       "                              [--unit UNIT] [--mapping MAP.json] [--fps N] [--time-limit S]\n"
       "       motionstyle-cli cleanup CLIPS... --out FOLDER [--metrics FOLDER] [--jobs N] [...]\n\n"
       "Solves every frame's joint rotations and root position with Ceres so that the clip's canonical\n"
       "joints stay where they are, while heels and toes stay locked during contact, no foot goes below\n"
       "the floor and bone lengths stay exactly the skeleton's. OUT keeps IN's hierarchy, joint names,\n"
       "offsets, channel layout and frame rate (or --fps); it is written atomically.\n\n"
       "  --contacts FILE   per-frame contact tracks (JSON, see core/ik/contact_file.h); default: the\n"
       "                    tracks saved beside the clip (IN.bvh.contacts.json) if any, else detected\n"
       "  --metrics FILE    write foot skate, floor penetration, bone error, residual and jerk before\n"
       "                    and after clean-up as JSON\n"
       "  --unit UNIT       the file's length unit (default: guessed; see info)\n"
       "  --mapping FILE    joint-mapping JSON for a rig the automatic mapping cannot read\n"
       "  --fps N           output frame rate (default: IN's own); the solve and metrics use IN's rate\n"
       MOTIONSTYLE_TIME_LIMIT_HELP MOTIONSTYLE_BATCH_HELP,
       runCleanup},
      {"eval", "evaluate a style network on held-out clips (JSON report)",
       "usage: motionstyle-cli eval [--loss-network LOSS] --net NET --style CLIP.bvh [--style LABEL=CLIP.bvh ...] CLIPS...\n"
       "                            [--json FILE] [--path content|style] [--refine-steps N]\n\n"
       "For each clip (files or folders): the loss network's reconstruction error (normalised MSE, mean joint\n"
       "error in cm; the familiarity reading: familiar, unusual, far), the content distance (eq. 4) and style distance (eq. 5, against the paired style clip)\n"
       "before and after stylizing (and the style distance of the projection decode(encode(.)) alone, to\n"
       "separate what the projection does from what the network does), bone-length error and foot skate\n"
       "(cm/s of feet labelled in contact) of\n"
       "the raw output, how far the network's own root path strays from the content's (distance ratio,\n"
       "end point error as a fraction of the distance), and run time; plus frame-weighted means. Use clips\n"
       "the network never trained on (train-* --holdout N lists them). Pairing as for train-style.\n\n"
       "  --json FILE   write the report to FILE (atomically) and print a summary; default: JSON on stdout\n"
       "  --path P      the output judged keeps the content's path (content, default) or the network's (style)\n"
       "  --refine-steps N\n"
       "                the style refinement's steps, as for stylize (default 30, 0 = the network's output)\n"
       "  --unit UNIT   length unit of the clips (default: guessed)\n",
       runEval},
      {"pack", "rewrite a network file with f16 (half the size) or f32 weights",
       "usage: motionstyle-cli pack IN.net --out OUT.net [--precision f16|f32]\n\n"
       "Reads a network file of either kind and any format version, and writes it atomically in the\n"
       "current format (core/nn/NETWORK_FORMAT.md) with its weights stored in the given precision.\n"
       "f16 (IEEE binary16, round to nearest even) halves the file; the networks still compute in f32.\n"
       "Weights outside f16's range (+-65504) are refused. Metadata and statistics are kept exactly.\n\n"
       "  --out FILE          the network file to write (may be IN itself)\n"
       "  --precision P       f16 (default) or f32\n",
       runPack},
      {"models", "list the networks shipped with MotionStyle (usable by name: --net elderly)",
       "usage: motionstyle-cli models [--json]\n\n"
       "Lists the default networks in the resources directory's models/ folder: name, kind (loss network\n"
       "or style), training epochs and style clips. Every option that takes a network file (--net, --loss-network,\n"
       "info) also takes such a name when no file of that name exists: --net elderly reads\n"
       "<resources>/models/elderly.net. The resources directory is $MOTIONSTYLE_RESOURCES if set, else the\n"
       "source tree's resources/ when run from a build tree, else <prefix>/share/motionstyle.\n\n"
       "  --json   print JSON instead of text\n",
       runModels},
  };
  return table;
}

}  // namespace motionstyle::cli
