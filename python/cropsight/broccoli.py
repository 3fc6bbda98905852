"""Broccoli heads from depth frames: detection (Montes et al. 2020), sizing, temporal filter and
field map (Kusumam et al. 2017). help(Config) lists every key of presets and sets={...}."""
from ._cropsight.broccoli import Config, Evaluator, FieldHead, FrameResult, Pipeline, PredictedHead
from ._cropsight import read_sequence

__all__ = ["Config", "Evaluator", "FieldHead", "FrameResult", "Pipeline", "PredictedHead", "evaluate"]


def evaluate(data, model="broccoli-oes-general", config="", sets=None):
    """The detection figures of `eval broccoli --json` (Table I / II) of a model over labelled
    sequence folders: `data` one folder or a list. The pipeline runs without tracking, as the
    command does without --track; each sequence is a pass of its own."""
    folders = [data] if isinstance(data, (str, bytes)) or hasattr(data, "__fspath__") else list(data)
    all_sets = dict(sets or {})
    all_sets["track"] = False
    pipe = Pipeline(model=model, config=config, sets=all_sets)
    evaluator = Evaluator(pipe)
    for folder in folders:
        seq = read_sequence(folder)
        if not seq.has_labels:
            raise ValueError(f"{folder}: sequence has no labels/ (evaluation needs ground truth)")
        pipe.reset()
        for frame in seq:
            evaluator.add_frame(frame)
    return evaluator.figures()
