"""`delvjax reproduce`: every study of the thesis in one run, and its report (docs/reproduce.md)."""

from ._study import RunConfig as RunConfig
from ._study import Settings as Settings
from ._study import StudyContext as StudyContext
